#!/usr/bin/env python3
"""multi_sync_turtlesim.launch markers:=true: every robot in tf, and the team's rviz view."""

import os
import sys
import unittest

import rospkg
import rospy
import rostest
from course_common.rviz.screen import error_lines
from course_common.rviz.snapshot import RvizOnXvfb
from course_common.testing import results_dir
from course_common.testing.views import TfPoseCheck
from turtlesim.msg import Pose

ROBOTS = ('robot_0', 'robot_1', 'robot_2', 'robot_3')
START_DEADLINE_S = 60.0  # roslaunch of the team, rosservice spawns, on a loaded machine
RVIZ_DEADLINE_S = 120.0  # rviz with software GL



class MultiSyncViewsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_multi_sync_views')

    def test_tf_has_world_to_every_robot_matching_its_pose(self):
        check = TfPoseCheck({r: '/%s/pose' % r for r in ROBOTS}, Pose)
        self.addCleanup(check.close)
        check.wait_agree(START_DEADLINE_S)

    def test_rviz_shows_the_team_view(self):
        path = os.path.join(rospkg.RosPack().get_path('multi_sync'), 'rviz',
                            'multi_sync_turtlesim.rviz')
        with RvizOnXvfb(path, 'rviz_under_test') as rviz:
            rviz.capture(os.path.join(results_dir(), 'multi_sync_rviz.png'), robots=len(ROBOTS),
                         labels=len(ROBOTS), timeout_s=RVIZ_DEADLINE_S)
            self.assertEqual(rviz.missing_topics(), [])
            self.assertEqual(rviz.topics, ['/lesson_markers', '/tf', '/tf_static'])
            self.assertEqual(error_lines(rviz.log()), [], rviz.log())


if __name__ == '__main__':
    rostest.rosrun('multi_sync', 'multi_sync_views', MultiSyncViewsTest, sys.argv)
