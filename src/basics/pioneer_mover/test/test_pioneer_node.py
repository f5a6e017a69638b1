#!/usr/bin/env python3
"""Integration test of pioneer.launch: the stand-in Pioneer's graph and Pose2D, and
pioneer_interface.py's quarter speed, from a Twist and from the teleop's arrow keys."""
import math
import unittest

import rospy
import rostest
from course_common.processes import ChildProcess
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, wait_for
from course_common.testing.master import publisher_has_connected, topic_types
from course_common.testing.recorders import LogRecorder, Recorder
from geometry_msgs.msg import Pose2D, Twist
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute

INTERFACE = '/pioneer_interface'
POSE_TOL = 1e-5  # float32 pose fields against float64 values
BANNER_LAST = "Use arrow keys to move the turtle. 'q' to quit."  # turtle_teleop_key's last line
CENTRE = (5.544445, 5.544445, 0.0)  # where the Pioneer spawns, heading +x: 5.5 m of room ahead


def _twist(lx=0.0, ly=0.0, az=0.0):
    twist = Twist()
    twist.linear.x, twist.linear.y, twist.angular.z = lx, ly, az
    return twist


def _values(twist):
    return (twist.linear.x, twist.linear.y, twist.linear.z,
            twist.angular.x, twist.angular.y, twist.angular.z)


class TestPioneer(unittest.TestCase):
    """Each test starts from where the Pioneer is, or puts it where it needs it: any order."""

    @classmethod
    def setUpClass(cls):
        cls.commands = Recorder('/pioneer/cmd_vel', Twist)
        cls.turtle = Recorder('/pioneer/turtle_pose', Pose, keep=1)
        cls.pose2d = Recorder('/pioneer/pose', Pose2D, keep=1)
        wait_for(lambda: cls.turtle.latest() and cls.pose2d.latest(), START_DEADLINE_S,
                 'the first /pioneer/turtle_pose and /pioneer/pose')
        wait_for(lambda: publisher_has_connected(INTERFACE, '/pioneer/cmd_vel', '/turtlesim'),
                 START_DEADLINE_S, 'pioneer_interface connected to the simulator')
        cls.logs = LogRecorder(INTERFACE)
        cls.teleop_cmd = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=10)
        rospy.wait_for_service('/pioneer/teleport_absolute', START_DEADLINE_S)
        cls.teleport = rospy.ServiceProxy('/pioneer/teleport_absolute', TeleportAbsolute)
        wait_for(lambda: publisher_has_connected(rospy.get_name(), '/turtle1/cmd_vel', INTERFACE),
                 START_DEADLINE_S, 'this test connected to pioneer_interface')
        wait_for(lambda: publisher_has_connected(INTERFACE, '/pioneer/cmd_vel', rospy.get_name()),
                 START_DEADLINE_S, 'pioneer_interface connected to this test')

    def _commands_after_clear(self, n, what):
        """The first n commands on /pioneer/cmd_vel since the last clear() (which comes before
        the publish, so a fast answer cannot be missed)."""
        wait_for(lambda: self.commands.count() >= n, EVENT_DEADLINE_S, what)
        return self.commands.messages()[:n]

    def test_graph_is_the_labs(self):
        types = topic_types()
        self.assertEqual(types['/pioneer/pose'], 'geometry_msgs/Pose2D')
        self.assertEqual(types['/pioneer/cmd_vel'], 'geometry_msgs/Twist')
        self.assertEqual(types['/pioneer/turtle_pose'], 'turtlesim/Pose')
        self.assertNotIn('/turtle1/pose', types, 'the turtle must live under /pioneer')

    def test_pose2d_is_the_turtles_pose(self):
        target = (3.0, 4.0, 1.0)
        pose = self._teleport(target)
        self.assertIsInstance(pose, Pose2D)

    def _teleport(self, target):
        """Teleports the Pioneer once it is at rest; returns its first Pose2D there.

        A moving turtle's first pose after a teleport already includes a tick of motion; the
        simulator stops it 1 s after the last command of an earlier test."""
        self.turtle.wait_latest(lambda p: p.linear_velocity == 0 and p.angular_velocity == 0,
                                'the Pioneer at rest')
        self.teleport(*target)
        return self.pose2d.wait_latest(
            lambda p: all(abs(a - b) < POSE_TOL
                          for a, b in zip((p.x, p.y, p.theta), target, strict=True)),
            'the Pose2D of the teleported turtle %r' % (target,))

    def test_command_divided_by_four(self):
        self.commands.clear()
        self.teleop_cmd.publish(_twist(2.0, 0.4, -1.2))
        got = self._commands_after_clear(1, 'the command on /pioneer/cmd_vel')[0]
        self.assertEqual(_values(got), (0.5, 0.1, 0.0, 0.0, 0.0, -0.3))
        self.logs.wait_line('The robot velocity is (2.0, -1.2)')
        self.turtle.wait_latest(lambda p: abs(p.angular_velocity + 0.3) < POSE_TOL,
                                'the Pioneer turning at -0.3 rad/s')

    def test_non_finite_command_never_reaches_the_robot(self):
        self.commands.clear()
        self.teleop_cmd.publish(_twist(math.nan, 0.0, 1.0))
        self.logs.wait_line('not forwarding')
        # A good command after the bad one: the first thing on /pioneer/cmd_vel must be it.
        self.teleop_cmd.publish(_twist(1.0))
        got = self._commands_after_clear(1, 'the good command after the NaN one')
        self.assertEqual([_values(m) for m in got], [(0.25, 0.0, 0.0, 0.0, 0.0, 0.0)])

    def test_teleop_arrow_keys_drive_at_quarter_speed(self):
        self._teleport(CENTRE)  # room to drive 0.1 m ahead, wherever other tests left it
        # as the lab, on a terminal of its own
        teleop = ChildProcess(('rosrun', 'turtlesim', 'turtle_teleop_key'), terminal=True).start()
        self.addCleanup(teleop.close)
        wait_for(lambda: BANNER_LAST in teleop.output(), START_DEADLINE_S, 'the teleop banner')
        wait_for(lambda: publisher_has_connected('/teleop_turtle', '/turtle1/cmd_vel', INTERFACE),
                 START_DEADLINE_S, 'the teleop connected to pioneer_interface')
        self.commands.clear()
        start = self.pose2d.latest()
        teleop.send(b'\x1b[A')  # up arrow: 2.0 m/s from the teleop
        got = self._commands_after_clear(1, 'the up-arrow command on /pioneer/cmd_vel')
        self.assertEqual(_values(got[0]), (0.5, 0.0, 0.0, 0.0, 0.0, 0.0))
        self.turtle.wait_latest(lambda p: p.linear_velocity == 0.5, 'the Pioneer at 0.5 m/s')
        self.pose2d.wait_latest(lambda p: math.hypot(p.x - start.x, p.y - start.y) > 0.1,
                                'the Pioneer 0.1 m from where it was')
        teleop.send(b'\x1b[D')  # left arrow: 2.0 rad/s from the teleop
        got = self._commands_after_clear(2, 'the left-arrow command on /pioneer/cmd_vel')
        self.assertEqual(_values(got[1]), (0.0, 0.0, 0.0, 0.0, 0.0, 0.5))
        self.logs.wait_line('The robot velocity is (0.0, 2.0)')
        teleop.send(b'q')
        self.assertEqual(teleop.proc.wait(timeout=EVENT_DEADLINE_S), 0)


if __name__ == '__main__':
    rospy.init_node('test_pioneer')
    rostest.rosrun('pioneer_mover', 'test_pioneer', TestPioneer)
