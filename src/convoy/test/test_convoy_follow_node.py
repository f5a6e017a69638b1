#!/usr/bin/env python3
"""Integration test: with the autopilot leader every follower catches up from the corner and
then stays within the stated gap of its leader (the course file for n = 3, the chain for more)."""
import unittest

import rosnode
import rospy
import rostest
from convoy_testing import CAUGHT_UP_M, STATED_GAP_M, ConvoyWatch
from course_common.testing import wait_for

PKG = 'convoy'
STARTUP_TIMEOUT_S = 40.0
# From the corner the last of 4 followers catches up in ~16 s of turtle time; margin for load.
CATCH_UP_TIMEOUT_S = 90.0
SETTLED_POSES = 500  # 8 s of poses at 62.5 Hz, a third of a lap of the figure eight
WORLD_MARGIN_M = 0.5  # the turtles never touch the walls (11.09 m world)


class TestConvoyFollows(unittest.TestCase):
    """Parameters: ~n (int): robots in the convoy; ~convoy_nodes (list of str): their nodes."""

    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_convoy_follow')
        cls.n = int(rospy.get_param('~n'))
        cls.watch = ConvoyWatch(cls.n)
        wait_for(cls.watch.all_seen, STARTUP_TIMEOUT_S, 'poses of robot1..robot%d' % cls.n)

    def test_nodes_of_the_chain(self):
        nodes = set(rosnode.get_node_names())
        expected = set(rospy.get_param('~convoy_nodes')) | {'/turtlesim', '/autopilot'}
        self.assertTrue(expected <= nodes, 'missing %s' % (expected - nodes))
        self.assertIsNone(self.watch.pose(self.n + 1))

    def test_followers_catch_up_then_keep_the_gap(self):
        followers = list(range(2, self.n + 1))
        for f in followers:
            wait_for(lambda f=f: self.watch.caught_up(f), CATCH_UP_TIMEOUT_S,
                     'robot%d to leave the corner and come within %.1f m of robot%d'
                     % (f, CAUGHT_UP_M, f - 1))
        start = {r: self.watch.travelled(r) for r in range(1, self.n + 1)}
        worst = self.watch.worst_gaps_over(followers, SETTLED_POSES, 60.0)
        for f, gap in worst.items():
            self.assertLessEqual(gap, STATED_GAP_M, 'robot%d fell %.2f m behind' % (f, gap))
        for robot in range(1, self.n + 1):
            pose = self.watch.pose(robot)
            self.assertGreater(min(pose.x, pose.y), WORLD_MARGIN_M)
            self.assertLess(max(pose.x, pose.y), 11.09 - WORLD_MARGIN_M)
            # A moving convoy, not a heap (the leader drives 4 m in these 8 s; followers cut
            # inside its curves, so they drive less).
            self.assertGreater(self.watch.travelled(robot) - start[robot], 1.0,
                               'robot%d hardly moved while settled' % robot)

if __name__ == '__main__':
    rostest.rosrun(PKG, 'convoy_follow', TestConvoyFollows)
