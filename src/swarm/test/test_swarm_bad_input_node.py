#!/usr/bin/env python3
"""rostest node: swarm_controller under bad input (see swarm_bad_input.test): clear WARNs,
commands for the robots that can have them, and both nodes still up at the end."""
import math
import unittest

import rosnode
import rospy
import rostest
from course_common.testing import START_DEADLINE_S, wait_for
from course_common.testing.master import publishers_of
from course_common.testing.recorders import LogRecorder, Recorder
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

NODES = ('/swarm_discover', '/swarm_five', '/swarm_from_one', '/swarm_past')
RATE_HZ = 10.0
WARN_DEADLINE_S = 30.0


RING_ANGLE_MIN_RAD = math.radians(-165.0)


def ring_scan(ranges, angle_min=RING_ANGLE_MIN_RAD):
    """A scan as stageros sends the swarm world's ring (12 beams, 30 degrees apart)."""
    return LaserScan(angle_min=angle_min, angle_max=-angle_min,
                     angle_increment=math.radians(30.0), range_min=0.0, range_max=2.0,
                     ranges=ranges, intensities=[0.0] * len(ranges))


SCANS = {0: ring_scan([0.4, 2.0, 2.0, 1.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0]),
         1: ring_scan([2.0, 2.0, 2.0, math.nan, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0]),
         2: ring_scan([2.0] * 12, angle_min=0.0)}


class TestSwarmBadInput(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        wait_for(lambda: all(n in publishers_of('/rosout') for n in NODES), START_DEADLINE_S,
                 'every controller up')
        cls.log = LogRecorder(None)
        cls.cmd = {i: Recorder('/robot_%d/cmd_vel' % i, Twist) for i in SCANS}

    def test_bad_input(self):
        # started before stageros: it waits, saying so
        self.log.wait_log('waiting for stageros', level=4, node='/swarm_discover',
                          timeout_s=WARN_DEADLINE_S)
        scan_pubs = {i: rospy.Publisher('/robot_%d/base_scan' % i, LaserScan, queue_size=1)
                     for i in SCANS}
        odom_pubs = {i: rospy.Publisher('/robot_%d/odom' % i, Odometry, queue_size=1)
                     for i in SCANS}

        def play(_):
            for i, pub in scan_pubs.items():
                pub.publish(SCANS[i])
                odom_pubs[i].publish(Odometry())
        timer = rospy.Timer(rospy.Duration(1.0 / RATE_HZ), play)
        try:
            self.log.wait_log('driving 3 robots', node='/swarm_discover',
                              timeout_s=WARN_DEADLINE_S)
            # robot_0: the law's command (blocked ahead: turning, not driving)
            wait_for(lambda: self.cmd[0].count(), WARN_DEADLINE_S, 'robot_0 commanded')
            first = self.cmd[0].latest()
            self.assertEqual(first.linear.x, 0.0)
            self.assertNotEqual(first.angular.z, 0.0)
            # robot_1: a NaN range: stopped, with a WARN naming the beam
            self.log.wait_log('beam 3 reads nan: stopping robot_1', level=4,
                              timeout_s=WARN_DEADLINE_S)
            wait_for(lambda: self.cmd[1].count(), WARN_DEADLINE_S, 'robot_1 commanded')
            self.assertEqual(self.cmd[1].latest(), Twist())
            # robot_2: not the ring: no command, a WARN
            self.log.wait_log('no beam looks along 0 degrees', level=4,
                              timeout_s=WARN_DEADLINE_S)
            self.assertEqual(self.cmd[2].count(), 0)
            # from robot_1 on: robot_1 and robot_2 (a team splitting the swarm)
            self.log.wait_log('driving 2 robots (robot_1 to robot_2)', node='/swarm_from_one',
                              timeout_s=WARN_DEADLINE_S)
            # from robot_7 on, of 3: nothing to drive yet, said
            self.log.wait_log('~first is 7 but stageros has 3 robots', level=4,
                              node='/swarm_past', timeout_s=WARN_DEADLINE_S)
            # told 5: robot_3 and robot_4 never send a scan
            self.log.wait_log('no scan yet from robot_3, robot_4 (2 in all)', level=4,
                              node='/swarm_five', timeout_s=WARN_DEADLINE_S)
        finally:
            timer.shutdown()
        # nothing broke: both still answer
        for node in NODES:
            self.assertTrue(rosnode.rosnode_ping(node, max_count=1), node)


if __name__ == '__main__':
    rospy.init_node('test_swarm_bad_input')
    rostest.rosrun('swarm', 'swarm_bad_input', TestSwarmBadInput)
