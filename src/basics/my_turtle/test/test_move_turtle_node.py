#!/usr/bin/env python3
"""Integration test of move_turtle: the slide's launch file (turtle1), turtle2 by argv, the wall,
shutdown, and bad command lines."""
import re
import signal
import unittest

import rosnode
import rospy
import rostest
from course_common.arena import WORLD_SIZE_M as WORLD
from course_common.testing import START_DEADLINE_S, spawn, wait_for
from course_common.testing.master import publisher_has_connected
from course_common.testing.recorders import LogRecorder, Recorder
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose
from turtlesim.srv import Spawn, TeleportAbsolute

SPEED_MPS = 0.5  # the slide's FORWARD_SPEED_MPS; exact in float32
MOVED_M = 0.2  # a turtle that went this far along +x is moving forward
POSE_LINE = re.compile(r'^x: \d+\.\d\d, y: \d+\.\d\d$')  # the slide's "x: %.2f, y: %.2f"
TURTLE2_START = (2.0, 2.0, 0.0)
TRACK_Y = 5.544445  # turtle1 spawns at the centre and drives along +x: y stays this
# Where a test that watches turtle1 drive puts it: on its track, 10 m from the right wall.
TURTLE1_START = (1.0, TRACK_Y, 0.0)


class TestMoveTurtle(unittest.TestCase):
    """The launch file's move_turtle drives turtle1 forward the whole time, into the right wall
    after ~11 s: a test that needs it driving puts it back on its track first, so the tests run
    in any order (and none moves turtle1 off its track, y = TRACK_Y)."""

    @classmethod
    def setUpClass(cls):
        rospy.wait_for_service('/spawn', START_DEADLINE_S)
        wait_for(lambda: '/move_turtle' in rosnode.get_node_names(), START_DEADLINE_S,
                 'the launch file\'s /move_turtle node')
        cls.turtle1 = Recorder('/turtle1/pose', Pose, keep=1)
        wait_for(cls.turtle1.latest, START_DEADLINE_S, 'the first /turtle1/pose')
        cls.teleport1 = rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)

    def _turtle1_to_start(self):
        self.teleport1(*TURTLE1_START)
        # Any x this far left leaves metres to drive (4 s to get past it at 0.5 m/s).
        self.turtle1.wait_latest(lambda p: p.x < TURTLE1_START[0] + 2.0
                                 and abs(p.y - TRACK_Y) < 1e-4,
                                 'turtle1 back near x = %.1f on its track' % TURTLE1_START[0])

    def _assert_drives_forward(self, poses, name):
        first = poses.wait_latest(lambda p: p.linear_velocity == SPEED_MPS,
                                  '%s commanded at %.1f m/s' % (name, SPEED_MPS))
        last = poses.wait_latest(lambda p: p.x > first.x + MOVED_M,
                                 '%s %.1f m further along +x' % (name, MOVED_M))
        self.assertAlmostEqual(last.y, first.y, delta=1e-4, msg='%s drifted sideways' % name)
        self.assertEqual(last.theta, first.theta, '%s turned' % name)

    def test_launch_file_drives_turtle1_forward(self):
        self._turtle1_to_start()
        self._assert_drives_forward(self.turtle1, 'turtle1')

    def test_launch_file_logs_the_pose(self):
        self._turtle1_to_start()
        logs = LogRecorder('/move_turtle')
        line = logs.wait_line('x: ')
        self.assertRegex(line, POSE_LINE)
        self.assertTrue(line.endswith('y: 5.54'), line)  # turtle1 drives along y = 5.544

    def test_turtle2_by_argv(self):
        rospy.ServiceProxy('/spawn', Spawn)(*TURTLE2_START, 'turtle2')
        poses = Recorder('/turtle2/pose', Pose, keep=1)
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

    def test_wall_gets_the_simulator_warning_not_a_crash(self):
        logs = LogRecorder('/turtlesim_node')
        self.teleport1(WORLD - 0.2, TRACK_Y, 0.0)
        logs.wait_line('Oh no! I hit the wall!')
        pinned = self.turtle1.wait_latest(
            lambda p: abs(p.x - WORLD) < 1e-4 and p.linear_velocity == SPEED_MPS,
            'turtle1 pinned at the right wall, still commanded')
        self.assertAlmostEqual(pinned.y, TRACK_Y, delta=1e-4)
        self.assertIn('/move_turtle', rosnode.get_node_names())
        self.assertEqual(rosnode.rosnode_ping('/move_turtle', max_count=1), True)

    def test_bad_argv_is_a_clear_error(self):
        # move_turtle2 of the turtle2 test unregisters in the background after its exit.
        wait_for(lambda: [n for n in rosnode.get_node_names() if n.startswith('/move_turtle')]
                 == ['/move_turtle'], START_DEADLINE_S, "the launch file's move_turtle alone")
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
