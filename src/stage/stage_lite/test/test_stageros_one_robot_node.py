#!/usr/bin/env python3
"""stageros with one robot: relative names in the node's namespace, its window, ~speedup."""
import time

import rostest
from course_common.testing.recorders import stamp_ns
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import LaserScan
from stage_support import (
    RANGE_TOL_M,
    START_DEADLINE_S,
    Recorder,
    StageTestCase,
    service_names,
    topic_types,
    wait_for,
)
from tf2_msgs.msg import TFMessage

NS = '/solo_ns/'
SPEEDUP = 20.0
#: Over WALL_WINDOW_S of wall time the simulation must get at least MIN_RATIO x as far: a
#: loose bound (a loaded machine may not reach 20 x) that real time (1 x) would fail.
WALL_WINDOW_S = 2.0
MIN_RATIO = 2.0


class StagerosOneRobotTest(StageTestCase):
    NODE_NAME = 'stageros_one_robot_test'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.logs = Recorder('/rosout', Log)

    def test_relative_names_in_the_namespace(self):
        def published():
            types = topic_types()
            return types if NS + 'base_scan' in types else None
        types = wait_for(published, START_DEADLINE_S, 'the one robot topics')
        for topic, msg_type in (('odom', 'nav_msgs/Odometry'),
                                ('base_pose_ground_truth', 'nav_msgs/Odometry'),
                                ('base_scan', 'sensor_msgs/LaserScan')):
            self.assertEqual(types[NS + topic], msg_type)
        self.assertFalse([t for t in types if 'robot_0' in t or t.startswith(NS + 'solo')])
        wait_for(lambda: NS + 'reset_positions' in service_names(), START_DEADLINE_S,
                 'the reset_positions service')
        self.assertIn('/clock', types)

    def test_frames_have_no_namespace(self):
        odom = Recorder(NS + 'odom', Odometry, keep=1).wait_first()
        self.assertEqual(odom.header.frame_id, 'odom')
        self.assertAlmostEqual(odom.pose.pose.position.x, 0.95, delta=1e-9)
        scan = Recorder(NS + 'base_scan', LaserScan, keep=1).wait_first()
        self.assertEqual(scan.header.frame_id, 'base_laser_link')
        self.assertEqual(len(scan.ranges), 181)
        self.assertAlmostEqual(scan.ranges[90], 1.95, delta=RANGE_TOL_M)  # wall face 2.95
        tf = Recorder('/tf', TFMessage, keep=1).wait_first()
        self.assertEqual({(t.header.frame_id, t.child_frame_id) for t in tf.transforms},
                         {('odom', 'base_footprint'), ('base_footprint', 'base_link'),
                          ('base_link', 'base_laser_link')})

    def test_window_opens_without_a_warning(self):
        self.logs.wait_where(lambda m: 'stageros:' in m.msg and 'x real time' in m.msg,
                             'the start-up line', START_DEADLINE_S)
        Recorder('/clock', Clock, keep=1).wait_first()
        self.assertFalse([m.msg for m in self.logs.messages()
                          if m.level >= Log.WARN and 'window' in m.msg])

    def test_speedup(self):
        line = self.logs.wait_where(lambda m: 'x real time' in m.msg, 'the start-up line',
                                    START_DEADLINE_S)
        self.assertIn('%g x real time' % SPEEDUP, line.msg)
        clock = Recorder('/clock', Clock, keep=1)
        first = stamp_ns(clock.wait_first())
        start = time.monotonic()
        wait_for(lambda: time.monotonic() - start >= WALL_WINDOW_S, WALL_WINDOW_S + 5,
                 'the measuring window')
        sim_s = (stamp_ns(clock.latest()) - first) * 1e-9
        self.assertGreater(sim_s, MIN_RATIO * WALL_WINDOW_S,
                           'sim time advanced %.2f s in %.1f s of wall time' % (sim_s,
                                                                             WALL_WINDOW_S))
        clock.close()


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_one_robot', StagerosOneRobotTest)
