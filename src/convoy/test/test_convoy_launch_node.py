#!/usr/bin/env python3
"""Integration test of the course's convoy.launch (no autopilot): topics, stop, kill/restart,
and convoy_node's fatal exit on missing or bad parameters."""
import os
import signal
import subprocess
import unittest

import rosgraph
import rosnode
import rospy
import rostest
from convoy_testing import TOLERANCE_M, ConvoyWatch, distance
from course_common.testing import wait_for
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose
from turtlesim.srv import TeleportAbsolute

PKG = 'convoy'
STARTUP_TIMEOUT_S = 30.0
DRIVE_TIMEOUT_S = 45.0  # from the corner to the centre takes ~8 s of turtle time; margin for load
STILL_POSES = 60  # about a second of poses at 62.5 Hz
CONVOY_NODE_ARGS = ['_leader_pose:=/robot1/pose', '_follower_pose:=/robot2/pose',
                    '_follower_speeds:=/robot2/cmd_vel']


def _topics():
    return {name for name, _ in rosgraph.Master('/test').getTopicTypes()}


class TestConvoyLaunch(unittest.TestCase):
    """The course file as students run it, leader left alone (nobody at the keyboard)."""

    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_convoy_launch')
        cls.watch = ConvoyWatch(3)
        cls.restarted = None
        wait_for(cls.watch.all_seen, STARTUP_TIMEOUT_S, 'poses of robot1, robot2 and robot3')

    @classmethod
    def tearDownClass(cls):
        if cls.restarted is not None and cls.restarted.poll() is None:
            cls.restarted.send_signal(signal.SIGINT)
            try:
                cls.restarted.wait(15)
            except subprocess.TimeoutExpired:
                cls.restarted.kill()

    def _wait_stopped_near(self, follower, timeout_s):
        """Waits until robot<follower> is inside the tolerance of its leader and still."""
        def stopped():
            pose = self.watch.pose(follower)
            return self.watch.gap(follower) < TOLERANCE_M and pose.linear_velocity == 0.0
        wait_for(stopped, timeout_s, 'robot%d to stop within %.1f m of robot%d'
                 % (follower, TOLERANCE_M, follower - 1))

    def _assert_still(self, robot):
        before = self.watch.pose(robot)
        count = self.watch.count(robot)
        wait_for(lambda: self.watch.count(robot) >= count + STILL_POSES, 10.0,
                 '%d poses of robot%d' % (STILL_POSES, robot))
        self.assertLess(distance(before, self.watch.pose(robot)), 0.01,
                        'robot%d moved while it should stand still' % robot)

    def test_1_course_topics_no_turtle1(self):
        topics = _topics()
        for robot in (1, 2, 3):
            for suffix in ('pose', 'cmd_vel'):
                self.assertIn('/robot%d/%s' % (robot, suffix), topics)
        self.assertEqual([t for t in topics if t.startswith('/turtle1')], [],
                         'the /turtle1 -> /robot1 remap must leave no /turtle1 topics')
        nodes = set(rosnode.get_node_names())
        self.assertTrue({'/turtlesim', '/convoy_node', '/convoy2_node'} <= nodes, nodes)

    def test_2_followers_stop_inside_tolerance(self):
        self._wait_stopped_near(2, DRIVE_TIMEOUT_S)
        self._wait_stopped_near(3, DRIVE_TIMEOUT_S)
        for follower in (2, 3):
            gap = self.watch.gap(follower)
            # It stops on the first pose inside: one 16 ms step at <= 0.45 m/s past the edge.
            self.assertGreater(gap, TOLERANCE_M - 0.1)
            command = self.watch.command(follower)
            self.assertEqual((command.linear.x, command.angular.z), (0.0, 0.0))
        self._assert_still(2)
        self._assert_still(3)

    def test_3_kill_and_restart_resumes(self):
        self._wait_stopped_near(2, DRIVE_TIMEOUT_S)
        rosnode.kill_nodes(['/convoy_node'])
        wait_for(lambda: '/convoy_node' not in rosnode.get_node_names(), 20.0,
                 '/convoy_node to exit after rosnode kill')
        # Move the leader away: with its convoy_node gone, robot2 must stay put.
        rospy.wait_for_service('/robot1/teleport_absolute', 10.0)
        rospy.ServiceProxy('/robot1/teleport_absolute', TeleportAbsolute)(9.0, 9.0, 0.0)
        wait_for(lambda: abs(self.watch.pose(1).x - 9.0) < 0.01, 10.0, 'robot1 at x = 9')
        self.assertGreater(self.watch.gap(2), TOLERANCE_M)
        self._assert_still(2)
        type(self).restarted = subprocess.Popen(
            ['rosrun', PKG, 'convoy_node', '__name:=convoy_node'] + CONVOY_NODE_ARGS,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=dict(os.environ))
        self._wait_stopped_near(2, DRIVE_TIMEOUT_S)
        self.assertIsNone(self.restarted.poll(), 'the restarted convoy_node exited')

    def test_4_missing_or_bad_params_are_fatal(self):
        # (name, executable, args, words the fatal message must contain); all run at once.
        cases = [
            ('bad_missing', 'convoy_node', [],
             ['~leader_pose', 'missing', 'non-empty topic name']),
            ('bad_empty', 'convoy_node', ['_leader_pose:=""'] + CONVOY_NODE_ARGS[1:],
             ['~leader_pose', "= ''", 'non-empty topic name']),
            ('bad_blank_speeds', 'convoy_node', CONVOY_NODE_ARGS[:2] + ['_follower_speeds:="  "'],
             ['~follower_speeds', 'non-empty topic name']),
            ('bad_type', 'convoy_node', ['_leader_pose:=5'] + CONVOY_NODE_ARGS[1:],
             ['~leader_pose', '5']),
            ('bad_gain', 'convoy_node', CONVOY_NODE_ARGS + ['_kp_lv:=-0.3'],
             ['~kp_lv', '-0.3', '>= 0']),
            ('bad_tolerance', 'convoy_node', CONVOY_NODE_ARGS + ['_distance_tolerance:=.nan'],
             ['~distance_tolerance', 'nan']),
            ('autopilot_bad_speed', 'autopilot', ['_speed:=-1.0'], ['~speed', '-1.0', '> 0']),
            ('autopilot_off_world', 'autopilot', ['_half_width:=6.0'], ['~half_width', 'walls']),
        ]
        procs = [subprocess.Popen(['rosrun', PKG, exe, '__name:=%s' % name] + args,
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                  env=dict(os.environ))
                 for name, exe, args, _ in cases]
        for (name, _, _, words), proc in zip(cases, procs, strict=True):
            with self.subTest(name=name):
                output, _ = proc.communicate(timeout=90)
                self.assertNotEqual(proc.returncode, 0, output)
                self.assertIn('FATAL', output)
                for word in words:
                    self.assertIn(word, output)
                self.assertNotIn('Traceback', output)

    def test_5_waits_for_both_poses_and_ignores_non_finite(self):
        # A second follower of robot2 whose leader is a topic this test publishes: no command
        # while the leader is unknown or NaN, commands once a finite leader pose arrives.
        commands = []
        sub = rospy.Subscriber('/fake/cmd_vel', Twist, commands.append)
        leader_pub = rospy.Publisher('/fake/leader_pose', Pose, queue_size=10)
        node = subprocess.Popen(
            ['rosrun', PKG, 'convoy_node', '__name:=convoy_fake', '_leader_pose:=/fake/leader_pose',
             '_follower_pose:=/robot2/pose', '_follower_speeds:=/fake/cmd_vel'],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=dict(os.environ))
        try:
            wait_for(lambda: leader_pub.get_num_connections() > 0 and sub.get_num_connections() > 0,
                     STARTUP_TIMEOUT_S, 'convoy_fake to connect')
            count = self.watch.count(2)
            wait_for(lambda: self.watch.count(2) >= count + STILL_POSES, 10.0, 'robot2 poses')
            self.assertEqual(commands, [], 'a command went out before the leader pose was known')
            leader_pub.publish(Pose(x=float('nan'), y=1.0, theta=0.0))
            count = self.watch.count(2)
            wait_for(lambda: self.watch.count(2) >= count + STILL_POSES, 10.0, 'robot2 poses')
            self.assertEqual(commands, [], 'a command went out for a NaN leader pose')
            leader_pub.publish(Pose(x=10.5, y=0.5, theta=0.0))
            wait_for(lambda: commands, 10.0, 'a command once the leader pose is finite')
            self.assertGreater(abs(commands[-1].angular.z) + commands[-1].linear.x, 0.0)
        finally:
            sub.unregister()
            node.send_signal(signal.SIGINT)
            output, _ = node.communicate(timeout=20)
        self.assertIn('ignoring a leader pose with non-finite fields', output)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'convoy_launch', TestConvoyLaunch)
