#!/usr/bin/env python3
"""stageros with four robots: what a user of stage_ros 1.8.0 sees through ROS."""
import math

import rospy
import rostest
from course_common.testing.recorders import stamp_ns
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import LaserScan
from stage_support import (
    EVENT_DEADLINE_S,
    POSE_TOL_M,
    RANGE_TOL_M,
    START_DEADLINE_S,
    STEP_NS,
    Recorder,
    StageTestCase,
    service_names,
    topic_types,
    wait_connected,
    wait_for,
)
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

ROBOTS = 4
STARTS = [(1.95, 1.0), (-0.05, 1.0), (1.95, -1.0), (-0.05, -1.0)]
RUN_STEPS = 20          # consecutive steps whose stamps are checked
SCAN_FOV_RAD = math.radians(270.25)


def _xy(msg):
    p = msg.pose.pose.position
    return p.x, p.y


class StagerosInterfaceTest(StageTestCase):
    NODE_NAME = 'stageros_interface_test'

    def test_names_and_types(self):
        expected = {'/clock': 'rosgraph_msgs/Clock', '/tf': 'tf2_msgs/TFMessage'}
        for n in range(ROBOTS):
            expected.update({'/robot_%d/odom' % n: 'nav_msgs/Odometry',
                             '/robot_%d/base_pose_ground_truth' % n: 'nav_msgs/Odometry',
                             '/robot_%d/base_scan' % n: 'sensor_msgs/LaserScan'})

        def published():
            types = topic_types()
            return types if all(t in types for t in expected) else None
        types = wait_for(published, START_DEADLINE_S, 'every stageros topic')
        for topic, msg_type in expected.items():
            self.assertEqual(types[topic], msg_type, topic)
        self.assertFalse([t for t in types if t.startswith('/robot_') and 'stall' in t],
                         'the stall topic is an extra, off by default')
        self.assertNotIn('/map', types)
        wait_for(lambda: '/reset_positions' in service_names(), START_DEADLINE_S,
                 'the reset_positions service')
        # stageros's services and rospy's own: ~save_image is an extra, off by default
        self.assertEqual(sorted(s for s in service_names() if s.startswith('/stageros/')
                                or s == '/reset_positions'),
                         ['/reset_positions', '/stageros/get_loggers',
                          '/stageros/set_logger_level'])
        self.assertIs(rospy.get_param('/use_sim_time'), True)

    def test_odom_and_ground_truth_at_the_start(self):
        for n, (x, y) in enumerate(STARTS):
            for topic in ('odom', 'base_pose_ground_truth'):
                rec = Recorder('/robot_%d/%s' % (n, topic), Odometry, keep=1)
                msg = rec.wait_first()
                rec.close()
                self.assertEqual(msg.header.frame_id, '/robot_%d/odom' % n)
                self.assertEqual(msg.child_frame_id, '')
                self.assertAlmostEqual(_xy(msg)[0], x, delta=POSE_TOL_M)
                self.assertAlmostEqual(_xy(msg)[1], y, delta=POSE_TOL_M)
                self.assertAlmostEqual(msg.pose.pose.orientation.w, 1.0, delta=POSE_TOL_M)
                self.assertFalse(any(msg.pose.covariance) or any(msg.twist.covariance))

    def test_every_topic_at_every_step_in_sim_time_and_clock_never_zero(self):
        recs = [Recorder('/clock', Clock), Recorder('/robot_1/odom', Odometry),
                Recorder('/robot_1/base_pose_ground_truth', Odometry),
                Recorder('/robot_1/base_scan', LaserScan), Recorder('/tf', TFMessage)]
        for rec in recs:
            wait_for(lambda r=rec: r.count() > RUN_STEPS + 2, EVENT_DEADLINE_S,
                     '%d messages on %s' % (RUN_STEPS + 2, rec.topic))
        for rec in recs:
            stamps = [stamp_ns(m) if rec.topic != '/tf' else stamp_ns(m.transforms[0])
                      for m in rec.messages()][1:RUN_STEPS + 1]
            rec.close()
            self.assertTrue(all(s > 0 for s in stamps), rec.topic)
            steps = {b - a for a, b in zip(stamps, stamps[1:], strict=False)}
            self.assertEqual(steps, {STEP_NS}, '%s: one message per 0.1 s of sim time'
                             % rec.topic)
        # roscpp numbers a publisher's messages whether anybody listens or not: stageros's
        # seq is the count of steps published before (t = 0.1 s is seq 0), joined mid-run.
        for topic, msg_class in (('/robot_1/odom', Odometry), ('/robot_1/base_scan', LaserScan)):
            rec = Recorder(topic, msg_class, keep=1)
            msg = rec.wait_first()
            rec.close()
            self.assertEqual(msg.header.seq, stamp_ns(msg) // STEP_NS - 1, topic)

    def test_tf_tree_with_leading_slashes(self):
        rec = Recorder('/tf', TFMessage, keep=1)
        msg = rec.wait_first()
        rec.close()
        pairs = {(t.header.frame_id, t.child_frame_id): t for t in msg.transforms}
        stamps = {stamp_ns(t) for t in msg.transforms}
        self.assertEqual(len(stamps), 1, 'every transform of a step has its stamp')
        for n in range(ROBOTS):
            p = '/robot_%d/' % n
            for parent, child in (('odom', 'base_footprint'), ('base_footprint', 'base_link'),
                                  ('base_link', 'base_laser_link')):
                self.assertIn((p + parent, p + child), pairs)
            laser = pairs[(p + 'base_link', p + 'base_laser_link')].transform.translation
            self.assertEqual((laser.x, laser.y, laser.z), (0.05, 0.0, 0.25))
        self.assertEqual(len(pairs), 3 * ROBOTS)

    def test_laser_scan_as_stage_fills_it(self):
        rec = Recorder('/robot_0/base_scan', LaserScan, keep=1)
        scan = rec.wait_first()
        rec.close()
        self.assertEqual(scan.header.frame_id, '/robot_0/base_laser_link')
        self.assertEqual(len(scan.ranges), 1081)
        self.assertEqual(len(scan.intensities), 1081)
        self.assertAlmostEqual(scan.angle_min, -SCAN_FOV_RAD / 2, delta=1e-6)
        self.assertAlmostEqual(scan.angle_max, SCAN_FOV_RAD / 2, delta=1e-6)
        self.assertAlmostEqual(scan.angle_increment, SCAN_FOV_RAD / 1080, delta=1e-8)
        self.assertEqual((scan.range_min, scan.range_max, scan.time_increment, scan.scan_time),
                         (0.0, 10.0, 0.0, 0.0))
        # Straight ahead: the east wall's face at x = 3.95, the laser at x = 2.0.
        self.assertAlmostEqual(scan.ranges[540], 1.95, delta=RANGE_TOL_M)
        self.assertEqual(set(scan.intensities), {1.0}, 'every beam meets a wall')

    def test_watchdog_stops_the_robot_three_steps_after_the_last_command(self):
        truth = Recorder('/robot_2/base_pose_ground_truth', Odometry, keep=1)
        start_x = _xy(truth.wait_first())[0]
        rec = Recorder('/robot_2/odom', Odometry)
        rec.wait_first()
        self.assertEqual(rec.latest().twist.twist.linear.x, 0.0, 'robot_2 at rest before')
        moving, stopped = self._one_command('/robot_2/cmd_vel', rec,
                                            Twist(linear=Vector3(0.1, 0, 0)),
                                            lambda m: m.twist.twist.linear.x)
        self.assertAlmostEqual(moving.twist.twist.linear.x, 0.1, delta=1e-9)
        # Received at step T: it moves at T+1 and T+2, the watchdog (0.2 s) stops it at T+3.
        # Exact whatever frames a loaded subscriber missed: two steps of 0.1 m/s, 0.02 m.
        at_rest = wait_for(lambda: truth.latest() if stamp_ns(truth.latest())
                           >= stamp_ns(stopped) else None, EVENT_DEADLINE_S,
                           'the ground truth of the stop')
        self.assertAlmostEqual(_xy(at_rest)[0] - start_x, 2 * 0.1 * STEP_NS / 1e9, delta=1e-9)
        late = [m for m in rec.messages() if stamp_ns(m) >= stamp_ns(moving) + 2 * STEP_NS
                and m.twist.twist.linear.x != 0]
        self.assertEqual(late, [], 'moving two steps after the first moving step')
        truth.close()
        rec.close()
        self._reset()

    def test_reset_positions_puts_every_robot_back(self):
        rec = Recorder('/robot_3/base_pose_ground_truth', Odometry, keep=1)
        odom = Recorder('/robot_3/odom', Odometry)
        rec.wait_first()
        odom.wait_first()
        _, stopped = self._one_command('/robot_3/cmd_vel', odom, Twist(angular=Vector3(0, 0, 0.5)),
                                       lambda m: m.twist.twist.angular.z)
        turned = wait_for(lambda: rec.latest() if stamp_ns(rec.latest()) >= stamp_ns(stopped)
                          else None, EVENT_DEADLINE_S, 'the ground truth of the stop')
        self.assertGreater(abs(turned.pose.pose.orientation.z), 0.04, 'robot_3 turned 0.1 rad')
        # As in Stage, reset_positions moves the robots back and leaves their velocity: robot_3
        # is at rest (the watchdog stopped it, and no command is on its way), so it stays put.
        self._reset()
        wait_for(lambda: abs(rec.latest().pose.pose.orientation.z) < POSE_TOL_M
                 and math.dist(_xy(rec.latest()), STARTS[3]) < POSE_TOL_M, EVENT_DEADLINE_S,
                 'robot_3 back at its start pose')
        rec.close()
        odom.close()

    def test_bad_commands_are_refused_with_a_warning(self):
        logs = Recorder('/rosout', Log)
        rec = Recorder('/robot_1/base_pose_ground_truth', Odometry, keep=1)
        pub = rospy.Publisher('/robot_1/cmd_vel', Twist, queue_size=10)
        wait_connected(pub, 'robot_1/cmd_vel')
        rec.wait_first()
        for bad in (math.nan, math.inf, -math.inf):
            pub.publish(Twist(linear=Vector3(bad, 0, 0)))
            pub.publish(Twist(angular=Vector3(0, 0, bad)))
        logs.wait_where(lambda m: m.level == Log.WARN and 'Ignoring cmd_vel' in m.msg
                        and '/robot_1/cmd_vel' in m.msg, 'the WARN about the bad command')
        first = stamp_ns(rec.latest())
        wait_for(lambda: stamp_ns(rec.latest()) > first + 5 * STEP_NS, EVENT_DEADLINE_S,
                 'five more steps')
        x, y = _xy(rec.latest())
        self.assertTrue(math.isfinite(x) and math.isfinite(y))
        self.assertAlmostEqual(x, STARTS[1][0], delta=POSE_TOL_M)
        self.assertAlmostEqual(y, STARTS[1][1], delta=POSE_TOL_M)
        logs.close()
        rec.close()

    @staticmethod
    def _one_command(topic, odom, twist, speed):
        """Publishes one command on topic; returns the first odom message (of `odom`, a
        Recorder) that moves with it and the first one after it at rest (the watchdog's
        stop). Once the stop is seen, nothing of this command is still on its way."""
        pub = rospy.Publisher(topic, Twist, queue_size=1)
        wait_connected(pub, topic)
        odom.clear()
        pub.publish(twist)
        moving = odom.wait_where(lambda m: speed(m) != 0, 'the commanded twist')
        stopped = odom.wait_where(lambda m: stamp_ns(m) > stamp_ns(moving) and speed(m) == 0,
                                  'the watchdog stopping it')
        pub.unregister()
        return moving, stopped

    @staticmethod
    def _reset():
        rospy.wait_for_service('/reset_positions', timeout=START_DEADLINE_S)
        rospy.ServiceProxy('/reset_positions', Empty)()


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_interface', StagerosInterfaceTest)
