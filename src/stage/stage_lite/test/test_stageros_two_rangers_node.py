#!/usr/bin/env python3
"""stageros with one robot and two rangers: relative robot names, absolute per-device names."""

import rostest
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from stage_support import (
    RANGE_TOL_M,
    START_DEADLINE_S,
    Recorder,
    StageTestCase,
    topic_types,
    wait_for,
)
from tf2_msgs.msg import TFMessage

NS = '/duo_ns/'
SCANS = ('/base_scan_0', '/base_scan_1')
LASER_FRAMES = ('/base_laser_link_0', '/base_laser_link_1')
#: Straight ahead of each laser (beam 90 of 181): the east wall's face 2 m ahead of the front
#: laser (x = 1.0), the west wall's face 3.7 m behind the rear one (x = 0.75).
AHEAD_M = (1.95, 3.70)


class StagerosTwoRangersTest(StageTestCase):
    NODE_NAME = 'stageros_two_rangers_test'

    def test_scan_topics_are_absolute_and_the_rest_relative(self):
        def published():
            types = topic_types()
            return types if all(s in types for s in SCANS) else None
        types = wait_for(published, START_DEADLINE_S, 'the two scan topics')
        for scan in SCANS:
            self.assertEqual(types[scan], 'sensor_msgs/LaserScan')
        self.assertEqual(types[NS + 'odom'], 'nav_msgs/Odometry')
        self.assertFalse([t for t in types if 'base_scan' in t and t not in SCANS])

    def test_scans_carry_absolute_laser_frames(self):
        for scan, frame, ahead in zip(SCANS, LASER_FRAMES, AHEAD_M, strict=True):
            msg = Recorder(scan, LaserScan, keep=1).wait_first()
            self.assertEqual(msg.header.frame_id, frame)
            self.assertAlmostEqual(msg.ranges[90], ahead, delta=RANGE_TOL_M)
        odom = Recorder(NS + 'odom', Odometry, keep=1).wait_first()
        self.assertEqual(odom.header.frame_id, 'odom')

    def test_tf_hangs_both_lasers_on_base_link(self):
        tf = Recorder('/tf', TFMessage, keep=1).wait_first()
        by_pair = {(t.header.frame_id, t.child_frame_id): t.transform for t in tf.transforms}
        self.assertEqual(set(by_pair), {('odom', 'base_footprint'),
                                        ('base_footprint', 'base_link'),
                                        ('base_link', LASER_FRAMES[0]),
                                        ('base_link', LASER_FRAMES[1])})
        rear = by_pair[('base_link', LASER_FRAMES[1])]
        self.assertAlmostEqual(rear.translation.x, -0.2, delta=1e-9)
        self.assertAlmostEqual(rear.translation.z, 0.25, delta=1e-9)
        self.assertAlmostEqual(abs(rear.rotation.z), 1.0, delta=1e-9)  # yaw 180 degrees


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_two_rangers', StagerosTwoRangersTest)
