#!/usr/bin/env python3
"""Integration test of move_turtle_to_goal.py on Stage's Pioneer 3-DX (Lab 2's task two with
pioneer.launch sim:=stage): goals in a row are reached within the lab's tolerances, in Stage's
room, by Stage's rules (its wheels held to the Pioneer's 0.5 m/s and 90 deg/s)."""
import math
import threading
import unittest

import rospy
import rostest
from course_common.angles import wrap_angle
from course_common.testing import START_DEADLINE_S, wait_for
from course_common.testing.recorders import LogRecorder, Recorder
from geometry_msgs.msg import Pose2D

CONTROLLER = '/move_turtle_to_goal'
# the longest goal below is ~6 m: at Stage's Pioneer's 0.5 m/s top speed, and turning at
# most 90 deg/s, under 30 s of simulated (= wall) time; margin for a loaded machine
GOAL_DEADLINE_S = 120.0
POSITION_TOL_M = 0.1  # the lab's tolerances...
HEADING_TOL_RAD = 0.05
# ...plus what the robot moves after the pose that met them: Stage moves it by the last
# command for up to two of its 0.1 s steps (the command reaches Stage between its steps; the
# controller saw a pose one step old) at what the law asks there: k_rho * 0.1 m = 0.314 m/s
# and k_beta * 0.05 rad = 0.15 rad/s, both below the Pioneer's limits
SLACK_M = 2 * 0.1 * 3.14 * 0.1
SLACK_RAD = 2 * 0.1 * 3.0 * 0.05


class LatestPose:
    """The newest /pioneer/pose."""

    def __init__(self):
        self._lock = threading.Lock()
        self._latest = None
        self._sub = rospy.Subscriber('/pioneer/pose', Pose2D, self._on_pose)

    def _on_pose(self, msg):
        with self._lock:
            self._latest = msg

    def __call__(self):
        with self._lock:
            return self._latest


class TestGoToGoalOnStage(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.pose = LatestPose()
        wait_for(cls.pose, START_DEADLINE_S, 'the first /pioneer/pose from Stage')
        cls.reached = Recorder('/pioneer/goal_reached', Pose2D)
        cls.goal_pub = rospy.Publisher('/pioneer/goal', Pose2D, queue_size=10)
        wait_for(lambda: cls.goal_pub.get_num_connections() > 0, START_DEADLINE_S,
                 "this test's goal publisher connected to the controller")
        cls.logs = LogRecorder(CONTROLLER)

    def _drive_to(self, goal):
        start = self.reached.count()
        self.goal_pub.publish(Pose2D(*goal))
        wait_for(lambda: any((m.x, m.y, m.theta) == goal
                             for m in self.reached.messages()[start:]),
                 GOAL_DEADLINE_S, 'goal %r reported on /pioneer/goal_reached' % (goal,))
        # the robot at rest: the last command (zero) has reached Stage
        wait_for(self._at_rest, GOAL_DEADLINE_S, 'the robot at rest after goal %r' % (goal,))
        pose = self.pose()
        self.assertLess(math.hypot(pose.x - goal[0], pose.y - goal[1]),
                        POSITION_TOL_M + SLACK_M, 'position at goal %r: %r' % (goal, pose))
        self.assertLess(abs(wrap_angle(pose.theta - goal[2])), HEADING_TOL_RAD + SLACK_RAD,
                        'heading at goal %r: %r' % (goal, pose))

    def _at_rest(self):
        """Two poses 0.1 s of simulated time apart are equal."""
        first = self.pose()
        rospy.sleep(0.25)          # sim time: at least two of Stage's steps
        last = self.pose()
        return (first.x, first.y, first.theta) == (last.x, last.y, last.theta)

    def test_goals_in_a_row_in_stages_room(self):
        start = self.pose()
        # behind the robot (it starts at the room's centre heading +x), then across the
        # heading seam, then the far corner: each reached, each reported once
        behind = (2.5, 5.0, 3.0)
        self.assertGreater(abs(wrap_angle(math.atan2(behind[1] - start.y, behind[0] - start.x)
                                          - start.theta)), math.pi / 2)
        lines = self.logs.lines().count('Reach orientation')
        for goal in (behind, (2.5, 5.0, -3.0), (8.0, 8.5, 1.0)):
            with self.subTest(goal=goal):
                self._drive_to(goal)
        wait_for(lambda: self.logs.lines().count('Reach orientation') == lines + 3, 15.0,
                 'three more "Reach orientation" lines')


if __name__ == '__main__':
    rospy.init_node('test_go_to_goal_stage')
    rostest.rosrun('closed_loop_turtle', 'test_go_to_goal_stage', TestGoToGoalOnStage)
