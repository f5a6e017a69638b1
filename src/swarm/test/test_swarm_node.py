#!/usr/bin/env python3
"""rostest node: swarm.launch with 10 swarmbots, watched through ROS: every robot is sent
commands, the robots move, and the swarm spreads out."""
import math
import unittest

import rospy
import rostest
from course_common.testing import wait_for
from course_common.testing.recorders import Recorder
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from swarm.spread import spread_m

ROBOTS = 10
# deadlines, generous for a loaded 2-core machine (they cost time only on failure)
LAUNCH_DEADLINE_S = 90.0
SPREAD_DEADLINE_S = 120.0
SPREAD_GAIN_M = 1.0        # the spread grows this much from the start (0.35 m)
MOVED_M = 0.2              # a robot that drove at least this far
MOST = 8                   # robots that must have moved (one may be boxed in a while)


def _xy(msg):
    p = msg.pose.pose.position
    return p.x, p.y


class TestSwarm(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.truth = [Recorder('/robot_%d/base_pose_ground_truth' % i, Odometry, keep=1)
                     for i in range(ROBOTS)]
        cls.cmd = [Recorder('/robot_%d/cmd_vel' % i, Twist, keep=1) for i in range(ROBOTS)]

    def test_the_swarm_moves_and_spreads(self):
        wait_for(lambda: all(r.count() for r in self.truth), LAUNCH_DEADLINE_S,
                 "every robot's ground truth")
        start = [_xy(r.latest()) for r in self.truth]
        wait_for(lambda: all(r.count() for r in self.cmd), LAUNCH_DEADLINE_S,
                 'a cmd_vel to every robot')
        wait_for(lambda: spread_m(_xy(r.latest()) for r in self.truth)
                 > spread_m(start) + SPREAD_GAIN_M, SPREAD_DEADLINE_S,
                 'the swarm to spread out by %g m' % SPREAD_GAIN_M)
        moved = [math.dist(a, _xy(r.latest())) for a, r in zip(start, self.truth, strict=True)]
        self.assertGreaterEqual(sum(m > MOVED_M for m in moved), MOST, moved)
        # commands are Stage's: 0.3 m/s or standing, turning by the law
        for r in self.cmd:
            self.assertIn(r.latest().linear.x, (0.0, 0.3))


if __name__ == '__main__':
    rospy.init_node('test_swarm')
    rostest.rosrun('swarm', 'swarm', TestSwarm)
