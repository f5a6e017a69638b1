#!/usr/bin/env python3
"""The simulator in the ROS graph: namespaces, remaps, private params, rosnode kill."""

import unittest

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, spawn, wait_for
from course_common.testing.master import graph_names, kill_node, published_topics, services
from course_common.testing.recorders import Recorder
from sim_support import DEFAULT_BG, TURTLE_SERVICES, TURTLE_TOPICS
from turtle_lite.testing import PoseRecorder
from turtlesim.msg import Color
from turtlesim.srv import Kill, Spawn

NODE_SERVICES = ("clear", "reset", "spawn", "kill")


def first_color(topic):
    """The (r, g, b) of the first Color message on topic."""
    colors = Recorder(topic, Color, queue_size=1)
    try:
        first = wait_for(colors.messages, EVENT_DEADLINE_S, f"a colour on {topic}")[0]
    finally:
        colors.close()
    return first.r, first.g, first.b


class RobustnessGraphTest(unittest.TestCase):
    def setUp(self):
        self.pose = PoseRecorder("/g1/turtle1/pose")
        self.addCleanup(self.pose.close)
        self.pose.wait_latest(lambda p: True, "the first pose", START_DEADLINE_S)

    def assert_turtle_at(self, namespace):
        topics, svcs = graph_names()
        for t in TURTLE_TOPICS:
            self.assertIn(f"{namespace}/{t}", topics)
        for s in TURTLE_SERVICES:
            self.assertIn(f"{namespace}/{s}", svcs)

    def test_group_namespace_holds_services_turtles_and_private_params(self):
        names = services()
        for s in NODE_SERVICES:
            self.assertIn(f"/g1/{s}", names)
            self.assertNotIn(f"/{s}", names)
            self.assertNotIn(f"/g1/sim/{s}", names)
        self.assert_turtle_at("/g1/turtle1")
        self.assertNotIn("/turtle1/pose", published_topics())
        # Params are private to the node: /g1/sim/background_*, written when absent.
        self.assertEqual(rospy.get_param("/g1/sim/background_r"), 69)
        self.assertEqual(rospy.get_param("/g1/sim/background_b"), 255)
        self.assertFalse(rospy.has_param("/g1/background_r"))
        self.assertFalse(rospy.has_param("/background_r"))

    def test_wrong_type_param_falls_back_to_default(self):
        # background_g = "green" (launch file): a warning, and the default 86 is used, so a
        # turtle at rest on the fresh canvas senses turtlesim's default background.
        self.assertEqual(rospy.get_param("/g1/sim/background_g"), "green")
        self.assertEqual(first_color("/g1/turtle1/color_sensor"), DEFAULT_BG)

    def test_relative_remap_applies_to_later_spawns(self):
        spawn = rospy.ServiceProxy("/g1/spawn", Spawn)
        kill = rospy.ServiceProxy("/g1/kill", Kill)
        self.assertEqual(spawn(2.0, 2.0, 0.0, "").name, "turtle2")
        wait_for(lambda: "/g1/r2/pose" in published_topics(), EVENT_DEADLINE_S,
                 "turtle2 on /g1/r2/pose")
        self.assert_turtle_at("/g1/r2")
        self.assertFalse({n for n in published_topics() if n.startswith("/g1/turtle2/")})
        # The turtle keeps its name: kill "r2" fails, kill "turtle2" removes /g1/r2/*.
        with self.assertRaises(rospy.ServiceException):
            kill("r2")
        kill("turtle2")
        wait_for(lambda: not {n for n in graph_names()[1] if n.startswith("/g1/r2/")},
                 EVENT_DEADLINE_S, "/g1/r2 services to leave the master")

    def test_ros_namespace_remap_bad_params_and_rosnode_kill(self):
        # A second simulator, run by the test so its output and exit code can be checked.
        # turtle1:=robot1 remaps the turtle's whole namespace (roscpp NodeHandle semantics).
        sim = spawn(["rosrun", "turtle_lite", "turtlesim_node", "turtle1:=robot1",
                    "_background_b:=blue", "_gui:=perhaps"], env={"ROS_NAMESPACE": "ns2"})
        self.addCleanup(sim.stop)
        wait_for(lambda: "/ns2/robot1/pose" in published_topics(), START_DEADLINE_S,
                 "/ns2/robot1/pose")
        sim.wait_line("Starting turtlesim with node name /ns2/turtlesim")
        sim.wait_line("Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]")
        self.assert_turtle_at("/ns2/robot1")
        self.assertFalse({n for n in graph_names()[0] | graph_names()[1]
                          if n.startswith("/ns2/turtle1")})
        self.assertIn("/ns2/spawn", services())
        self.assertEqual(rospy.get_param("/ns2/turtlesim/background_r"), 69)
        self.assertIn("WARN", sim.wait_line("background_b"))
        self.assertIn("WARN", sim.wait_line("gui"))
        self.assertEqual(first_color("/ns2/robot1/color_sensor"), DEFAULT_BG)

        kill_node("/ns2/turtlesim")
        self.assertEqual(sim.wait_exit(EVENT_DEADLINE_S), 0)
        self.assertTrue(sim.lines_with("Shutdown request received."), sim.output())
        self.assertTrue(sim.lines_with("Reason given for shutdown: [user request]"),
                        sim.output())
        self.assertFalse({n for n in published_topics() if n.startswith("/ns2/")})
        # The simulator in the group is untouched.
        count = self.pose.count()
        wait_for(lambda: self.pose.count() > count + 5, EVENT_DEADLINE_S,
                 "/g1/turtle1/pose still flowing")


if __name__ == "__main__":
    rospy.init_node("test_robustness_graph")
    rostest.rosrun("turtle_lite", "robustness_graph", RobustnessGraphTest)
