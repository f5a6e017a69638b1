#!/usr/bin/env python3
"""Integration test of move_turtle: the slide's launch file (turtle1), turtle2 by argv, the wall,
shutdown, and bad command lines."""
import re
import signal
import unittest

import rosnode
import rospy
import rostest
from course_common.testing import START_DEADLINE_S, spawn, wait_for
from course_common.testing.master import publisher_has_connected
from course_common.testing.recorders import LogRecorder, Recorder
from course_common.testing.turtlesim import WORLD, PoseRecorder
from geometry_msgs.msg import Twist
from turtlesim.srv import Spawn, TeleportAbsolute

SPEED_MPS = 0.5  # the slide's FORWARD_SPEED_MPS; exact in float32
MOVED_M = 0.2  # a turtle that went this far along +x is moving forward
POSE_LINE = re.compile(r'^x: \d+\.\d\d, y: \d+\.\d\d$')  # the slide's "x: %.2f, y: %.2f"
TURTLE2_START = (2.0, 2.0, 0.0)


class TestMoveTurtle(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service('/spawn', START_DEADLINE_S)
        wait_for(lambda: '/move_turtle' in rosnode.get_node_names(), START_DEADLINE_S,
                 'the launch file\'s /move_turtle node')
        cls.turtle1 = PoseRecorder('/turtle1/pose', keep=1)
        wait_for(cls.turtle1.latest, START_DEADLINE_S, 'the first /turtle1/pose')

    def _assert_drives_forward(self, poses, name):
        first = poses.wait_latest(lambda p: p.linear_velocity == SPEED_MPS,
                                  '%s commanded at %.1f m/s' % (name, SPEED_MPS))
        last = poses.wait_latest(lambda p: p.x > first.x + MOVED_M,
                                 '%s %.1f m further along +x' % (name, MOVED_M))
        self.assertAlmostEqual(last.y, first.y, delta=1e-4, msg='%s drifted sideways' % name)
        self.assertEqual(last.theta, first.theta, '%s turned' % name)

    def test_1_launch_file_drives_turtle1_forward(self):
        self._assert_drives_forward(self.turtle1, 'turtle1')

    def test_2_launch_file_logs_the_pose(self):
        logs = LogRecorder('/move_turtle')
        line = logs.wait_line('x: ')
        self.assertRegex(line, POSE_LINE)
        self.assertTrue(line.endswith('y: 5.54'), line)  # turtle1 drives along y = 5.544

    def test_3_turtle2_by_argv(self):
        rospy.ServiceProxy('/spawn', Spawn)(*TURTLE2_START, 'turtle2')
        poses = PoseRecorder('/turtle2/pose', keep=1)
        commands = Recorder('/turtle2/cmd_vel', Twist)
        tool = spawn(['rosrun', 'my_turtle', 'move_turtle', 'turtle2', '__name:=move_turtle2'])
        self.addCleanup(tool.stop)
        tool.wait_line('Starting to move forward', START_DEADLINE_S)
        line = tool.wait_line('x: ').split(']: ', 1)[1]  # after rospy's "[INFO] [stamp]: "
        self.assertRegex(line, POSE_LINE)
        self.assertTrue(line.endswith('y: 2.00'), line)
        self._assert_drives_forward(poses, 'turtle2')
        # Ctrl-C: the node sends a zero Twist, exits cleanly, and the turtle comes to rest.
        wait_for(lambda: publisher_has_connected('/move_turtle2', '/turtle2/cmd_vel'),
                 START_DEADLINE_S, 'move_turtle2 connected to this test')
        tool.proc.send_signal(signal.SIGINT)
        self.assertEqual(tool.wait_exit(), 0, tool.output())
        last = commands.wait_latest(lambda m: m.linear.x == 0.0, 'the zero Twist at shutdown')
        self.assertEqual((last.linear.x, last.angular.z), (0.0, 0.0))
        poses.wait_latest(lambda p: p.linear_velocity == 0.0, 'turtle2 at rest after Ctrl-C')

    def test_4_wall_gets_the_simulator_warning_not_a_crash(self):
        logs = LogRecorder('/turtlesim_node')
        rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(WORLD - 0.2, 5.5, 0.0)
        logs.wait_line('Oh no! I hit the wall!')
        pinned = self.turtle1.wait_latest(
            lambda p: abs(p.x - WORLD) < 1e-4 and p.linear_velocity == SPEED_MPS,
            'turtle1 pinned at the right wall, still commanded')
        self.assertAlmostEqual(pinned.y, 5.5, delta=1e-4)
        self.assertIn('/move_turtle', rosnode.get_node_names())
        self.assertEqual(rosnode.rosnode_ping('/move_turtle', max_count=1), True)

    def test_5_bad_argv_is_a_clear_error(self):
        cases = ((['my turtle'], 'not a valid ROS name'),
                 (['turtle2', 'turtle3'], 'at most one robot name, got 2'),
                 (['~mine'], 'is private'))
        for args, words in cases:
            with self.subTest(args=args):
                tool = spawn(['rosrun', 'my_turtle', 'move_turtle', *args])
                self.addCleanup(tool.stop)
                self.assertEqual(tool.wait_exit(START_DEADLINE_S), 1, tool.output())
                self.assertTrue(tool.lines_with(words), tool.output())
                self.assertTrue(tool.lines_with('usage: rosrun my_turtle move_turtle'),
                                tool.output())
        self.assertEqual([n for n in rosnode.get_node_names() if n.startswith('/move_turtle')],
                         ['/move_turtle'], 'a bad command line must not register a node')


if __name__ == '__main__':
    rospy.init_node('test_move_turtle')
    rostest.rosrun('my_turtle', 'test_move_turtle', TestMoveTurtle)
