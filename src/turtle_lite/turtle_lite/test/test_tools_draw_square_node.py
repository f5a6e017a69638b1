#!/usr/bin/env python3
"""draw_square resets the simulator, then drives turtle1 2 m along +x and turns left."""

import math
import unittest

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, spawn, wait_for
from course_common.testing.master import published_topics, subscribed_topics
from turtle_lite.testing import CENTER, PoseRecorder
from turtlesim.srv import Spawn, TeleportAbsolute

POSE_TOL = 1e-4  # float32 poses, printed goals with 6 decimals
# The side takes about 2 s of pose ticks, the turn about 4 s; allow for a loaded machine.
SIDE_DEADLINE_S = 40.0


class DrawSquareTest(unittest.TestCase):
    def setUp(self):
        rospy.wait_for_service("/turtle1/teleport_absolute", START_DEADLINE_S)
        self.pose = PoseRecorder("/turtle1/pose")
        self.addCleanup(self.pose.close)

    def test_resets_then_drives_the_first_side_and_turns(self):
        # A scene that only a reset undoes: turtle1 moved away and a second turtle.
        rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)(2.0, 3.0, 1.0)
        rospy.ServiceProxy("/spawn", Spawn)(8.0, 8.0, 0.0, "turtle2")
        self.pose.wait_latest(lambda p: abs(p.x - 2.0) < POSE_TOL, "the teleported turtle1")
        wait_for(lambda: "/turtle2/pose" in published_topics(), EVENT_DEADLINE_S,
                 "/turtle2/pose to be advertised")

        tool = spawn(["rosrun", "turtle_lite", "draw_square"])
        self.addCleanup(tool.stop)
        # The reset removed turtle2 and put turtle1 back at the centre, heading 0.
        wait_for(lambda: "/turtle2/pose" not in published_topics(), START_DEADLINE_S,
                 "reset to remove turtle2")
        first = tool.wait_line("New goal [", START_DEADLINE_S)
        self.assertIn("New goal [7.544445 5.544445, 0.000000]", first)

        # First side: along +x at y = centre, then "Reached goal" and a left-turn goal.
        tool.wait_line("Reached goal", SIDE_DEADLINE_S)
        second = wait_for(lambda: tool.lines_with("New goal [")[1:], EVENT_DEADLINE_S,
                          "the second goal")[0]
        x, y, theta = (float(v) for v in
                       second.split("New goal [")[1].rstrip("]").replace(",", "").split())
        self.assertAlmostEqual(y, CENTER, delta=POSE_TOL)
        self.assertLess(abs(x - (CENTER + 2.0)), 0.1)
        self.assertAlmostEqual(theta, 1.570796, delta=1e-6)
        stopped = self.pose.latest()
        self.assertAlmostEqual(stopped.y, CENTER, delta=POSE_TOL)
        self.assertLess(abs(stopped.x - (CENTER + 2.0)), 0.1)

        # Then it turns on the spot, counter-clockwise, towards +y.
        turning = self.pose.wait_latest(lambda p: p.theta > 0.5, "turtle1 turning left",
                                        SIDE_DEADLINE_S)
        self.assertAlmostEqual(turning.x, x, delta=POSE_TOL)
        self.assertAlmostEqual(turning.angular_velocity, 0.4, delta=1e-6)
        self.assertTrue(math.isclose(turning.linear_velocity, 0.0, abs_tol=1e-9))

    def test_without_simulator_warns_and_keeps_running(self):
        # In a namespace with no simulator, reset is unavailable: a warning, not a crash.
        tool = spawn(["rosrun", "turtle_lite", "draw_square", "__name:=square_alone"],
                    env={"ROS_NAMESPACE": "nosim"})
        self.addCleanup(tool.stop)
        warning = tool.wait_line("could not call /nosim/reset", START_DEADLINE_S)
        self.assertIn("WARN", warning)
        wait_for(lambda: "/nosim/turtle1/pose" in subscribed_topics(), EVENT_DEADLINE_S,
                 "draw_square to subscribe /nosim/turtle1/pose after the failed reset")
        self.assertIsNone(tool.proc.poll(), "draw_square should keep running")


if __name__ == "__main__":
    rospy.init_node("test_tools_draw_square")
    rostest.rosrun("turtle_lite", "tools_draw_square", DrawSquareTest)
