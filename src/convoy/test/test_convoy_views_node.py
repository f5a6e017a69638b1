#!/usr/bin/env python3
"""convoy.launch markers:=true: every robot in tf, the gap labels, the convoy's rviz view."""

import math
import os
import subprocess
import sys
import threading
import unittest

import rospkg
import rospy
import rostest
from course_common.rviz.screen import error_lines
from course_common.rviz.snapshot import RvizOnXvfb
from course_common.testing import results_dir, wait_for
from course_common.testing.views import TfPoseCheck
from turtlesim.msg import Pose
from visualization_msgs.msg import MarkerArray

ROBOTS = ('robot1', 'robot2', 'robot3')
START_DEADLINE_S = 60.0  # roslaunch of six nodes, rosservice spawns, on a loaded machine
SETTLE_DEADLINE_S = 120.0  # followers drive from (0, 0) to within 1.5 m of robot1 and stop
RVIZ_DEADLINE_S = 120.0  # rviz with software GL
LABEL_TOL_M = 0.01  # the label's two decimals



class ConvoyViewsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_convoy_views')
        cls.lock = threading.Lock()
        cls.poses = {}
        cls.gaps = None
        cls.subs = [rospy.Subscriber('/%s/pose' % r, Pose, cls._on_pose, callback_args=r,
                                     queue_size=1) for r in ROBOTS]
        cls.subs.append(rospy.Subscriber('/convoy_gaps', MarkerArray, cls._on_gaps,
                                         queue_size=1))

    @classmethod
    def _on_pose(cls, msg, robot):
        with cls.lock:
            cls.poses[robot] = msg

    @classmethod
    def _on_gaps(cls, msg):
        cls.gaps = msg

    def test_tf_has_world_to_every_robot_matching_its_pose(self):
        check = TfPoseCheck({r: '/%s/pose' % r for r in ROBOTS}, Pose)
        self.addCleanup(check.close)
        # robot1 stands still: tf agrees at once; the followers agree when they stop (or
        # between two poses), and a wrong transform never agrees.
        check.wait_agree(START_DEADLINE_S, ['robot1'])
        check.wait_agree(SETTLE_DEADLINE_S)

    def label_matches_poses(self):
        msg = self.gaps
        with self.lock:
            poses = dict(self.poses)
        if msg is None or len(poses) < len(ROBOTS):
            return None
        texts = {m.ns + str(m.id): m for m in msg.markers}
        for marker_id, (follower, leader) in enumerate((('robot2', 'robot1'),
                                                        ('robot3', 'robot2'))):
            text = texts.get('gap%d' % marker_id)
            if text is None or not text.text.startswith('%s -> %s ' % (follower, leader)):
                return None
            shown = float(text.text.split()[-2])
            gap = math.hypot(poses[follower].x - poses[leader].x,
                             poses[follower].y - poses[leader].y)
            if abs(shown - gap) > LABEL_TOL_M or text.header.frame_id != 'world':
                return None
        return True

    def test_gap_labels_show_each_followers_distance(self):
        wait_for(self.label_matches_poses, SETTLE_DEADLINE_S,
                 'gap labels robot2 -> robot1 and robot3 -> robot2 equal to the pose distances')

    def test_convoy_gaps_rejects_a_convoy_of_one(self):
        result = subprocess.run(['rosrun', 'convoy', 'convoy_gaps', '_robots:=[robot1]',
                                 '__name:=bad_convoy_gaps'], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True,
                                timeout=START_DEADLINE_S)
        self.assertNotEqual(result.returncode, 0, result.stdout)
        self.assertIn("parameter ~robots = ['robot1']", result.stdout)

    def test_rviz_shows_the_convoy_view(self):
        path = os.path.join(rospkg.RosPack().get_path('convoy'), 'rviz', 'convoy.rviz')
        with RvizOnXvfb(path, 'rviz_under_test') as rviz:
            rviz.capture(os.path.join(results_dir(), 'convoy_rviz.png'), robots=3, labels=5,
                         timeout_s=RVIZ_DEADLINE_S)
            self.assertEqual(rviz.missing_topics(), [])
            self.assertEqual(rviz.topics,
                             ['/convoy_gaps', '/lesson_markers', '/tf', '/tf_static'])
            self.assertEqual(error_lines(rviz.log()), [], rviz.log())


if __name__ == '__main__':
    rostest.rosrun('convoy', 'convoy_views', ConvoyViewsTest, sys.argv)
