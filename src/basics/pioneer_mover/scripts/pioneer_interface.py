#!/usr/bin/python3
from pioneer_mover.pioneer_interface_node import main

main()
