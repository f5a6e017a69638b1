#!/usr/bin/python3
from closed_loop_turtle.move_turtle_to_goal_node import main

main()
