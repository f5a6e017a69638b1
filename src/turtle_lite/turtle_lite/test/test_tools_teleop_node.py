#!/usr/bin/env python3
"""turtle_teleop_key driven through a pseudo-terminal: keys in, Twists out, terminal restored."""

import signal
import termios
import unittest

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, spawn, wait_for
from course_common.testing.master import kill_node, publisher_has_connected
from course_common.testing.recorders import Recorder
from geometry_msgs.msg import Twist
from turtle_lite.testing import run_teleop

BANNER_LAST = "Use arrow keys to move the turtle. 'q' to quit."


class TeleopTest(unittest.TestCase):
    def setUp(self):
        self.twists = Recorder("/turtle1/cmd_vel", Twist)
        self.addCleanup(self.twists.close)
        self.teleop = None

    def start_teleop(self, env_extra=None):
        self.teleop = run_teleop(env=env_extra)
        self.addCleanup(self.teleop.close)

    def received(self):
        """Every Twist received, as (linear.x, .y, .z, angular.x, .y, .z)."""
        return [(m.linear.x, m.linear.y, m.linear.z, m.angular.x, m.angular.y, m.angular.z)
                for m in self.twists.messages()]

    def wait_ready(self, env_extra=None):
        self.start_teleop(env_extra)
        wait_for(lambda: BANNER_LAST in self.teleop.output(), START_DEADLINE_S,
                 "the teleop banner")
        wait_for(lambda: publisher_has_connected("/teleop_turtle", "/turtle1/cmd_vel"),
                 START_DEADLINE_S, "teleop's cmd_vel publisher to connect")
        wait_for(lambda: not self.teleop.terminal_lflags() & termios.ICANON, EVENT_DEADLINE_S,
                 "teleop to switch the terminal to non-canonical mode")

    def test_keys_publish_one_twist_each_and_q_quits(self):
        self.wait_ready()
        out = self.teleop.output()
        for line in ("Reading from keyboard", "---------------------------", BANNER_LAST):
            self.assertIn(line, out)
        self.assertFalse(self.teleop.terminal_lflags() & termios.ECHO, "teleop should disable echo")

        # Up arrow, a plain 'A' (turtlesim quirk), an ignored 'x' followed by the left arrow,
        # down arrow. One key at a time, like a typist: the publisher's queue holds 1, so a
        # burst of keys may legitimately lose all but the newest Twist on a loaded machine.
        for count, keys in enumerate((b"\x1b[A", b"A", b"x\x1b[D", b"\x1b[B"), start=1):
            self.teleop.send(keys)
            wait_for(lambda n=count: len(self.received()) >= n, EVENT_DEADLINE_S,
                     f"Twist number {count} (after {keys!r})")
        self.teleop.send(b"q")
        code = self.teleop.proc.wait(timeout=EVENT_DEADLINE_S)
        self.assertEqual(code, 0)
        # /scale_linear = 3.0 from the launch file; scale_angular keeps its default 2.0.
        self.assertEqual(self.received(), [
            (3.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            (3.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            (0.0, 0.0, 0.0, 0.0, 0.0, 2.0),
            (-3.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        ])
        lflags = self.teleop.terminal_lflags()
        self.assertTrue(lflags & termios.ICANON and lflags & termios.ECHO,
                        "the terminal should be restored after q")

    def test_sigint_restores_terminal(self):
        self.wait_ready()
        self.teleop.send(b"\x1b[C")
        wait_for(lambda: self.received(), EVENT_DEADLINE_S, "the right-arrow Twist")
        self.assertEqual(self.received(), [(0.0, 0.0, 0.0, 0.0, 0.0, -2.0)])
        self.teleop.proc.send_signal(signal.SIGINT)
        code = self.teleop.proc.wait(timeout=EVENT_DEADLINE_S)
        self.assertEqual(code, 0)
        lflags = self.teleop.terminal_lflags()
        self.assertTrue(lflags & termios.ICANON and lflags & termios.ECHO,
                        "the terminal should be restored after SIGINT")

    def test_rosnode_kill_restores_terminal(self):
        self.wait_ready()
        kill_node("/teleop_turtle")
        self.assertEqual(self.teleop.proc.wait(timeout=EVENT_DEADLINE_S), 0)
        lflags = self.teleop.terminal_lflags()
        self.assertTrue(lflags & termios.ICANON and lflags & termios.ECHO,
                        "the terminal should be restored after rosnode kill")

    def test_bad_scale_param_is_fatal(self):
        # In its own namespace so the other tests keep the launch file's parameters.
        rospy.set_param("/badns/scale_angular", "fast")
        self.start_teleop({"ROS_NAMESPACE": "badns"})
        self.assertEqual(self.teleop.proc.wait(timeout=START_DEADLINE_S), 1)
        wait_for(lambda: "parameter scale_angular = 'fast': expected a finite number"
                 in self.teleop.output(),
                 EVENT_DEADLINE_S, "the fatal message naming the parameter")
        self.assertEqual(self.received(), [])

    def test_terminal_hang_up_ends_the_teleop(self):
        self.wait_ready()
        self.teleop.hang_up()
        # SIGHUP (as for turtlesim's teleop) or, if it is ignored, the read error: exit 1.
        code = self.teleop.proc.wait(timeout=EVENT_DEADLINE_S)
        self.assertIn(code, (1, -signal.SIGHUP))

    def test_stdin_not_a_tty_fails_clearly(self):
        tool = spawn(["rosrun", "turtle_lite", "turtle_teleop_key"])
        try:
            code = tool.wait_exit(START_DEADLINE_S)
            self.assertNotEqual(code, 0)
            self.assertTrue(tool.lines_with("stdin is not a terminal"), tool.output())
        finally:
            tool.stop()


if __name__ == "__main__":
    rospy.init_node("test_tools_teleop")
    rostest.rosrun("turtle_lite", "tools_teleop", TeleopTest)
