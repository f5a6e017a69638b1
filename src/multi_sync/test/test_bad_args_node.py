#!/usr/bin/env python3
"""rostest node: bad argv and parameters of the nodes give the lesson's message and exit 1."""
import sys
import unittest

import rospy
import rostest
from course_common.testing import check_refused

TEAM_SIZE_RANGE = 'The team size must be an integer number between 1 and 20'
ROBOT_ID_RANGE = "The robot's ID must be an integer number between 0 and 19"

CASES = [
    # (arguments after rosrun multi_sync, expected text in the output)
    (['monitor'], 'You must specify team size.'),
    (['monitor', '0'], TEAM_SIZE_RANGE),
    (['monitor', '21'], TEAM_SIZE_RANGE),
    (['monitor', '-4'], TEAM_SIZE_RANGE),
    (['monitor', 'four'], TEAM_SIZE_RANGE),
    (['monitor', '4.5'], TEAM_SIZE_RANGE),
    (['monitor', '4abc'], TEAM_SIZE_RANGE),
    (['monitor', ''], TEAM_SIZE_RANGE),
    (['move_robot'], 'You must specify robot id.'),
    (['move_robot', '20'], ROBOT_ID_RANGE),
    (['move_robot', '-1'], ROBOT_ID_RANGE),
    (['move_robot', 'one'], ROBOT_ID_RANGE),
    (['move_robot', '1.0'], ROBOT_ID_RANGE),
    # move_robot_sync: the Stage lesson's name for the node, on Stage's inputs only
    # (multi_sync.launch starts it)
    (['move_robot_sync'], 'You must specify robot id.'),
    (['move_robot_sync', '20'], ROBOT_ID_RANGE),
    (['move_robot_sync', '-1'], ROBOT_ID_RANGE),
    (['move_robot_sync', 'one'], ROBOT_ID_RANGE),
    # parameters are checked after init_node: fatal, naming the parameter
    (['move_robot', '1', '_speed_mps:=-0.2'], 'parameter ~speed_mps = -0.2'),
    (['move_robot', '1', '_rate_hz:=0'], 'parameter ~rate_hz = 0'),
    (['move_robot', '1', '_stop_distance_m:=.nan'], 'parameter ~stop_distance_m = nan'),
    (['move_robot', '1', '_min_gap_m:=far'], "parameter ~min_gap_m = 'far'"),
    # move_robot (either simulator): a bumper beyond both simulators' bounds, refused before
    # a pose names the simulator (start_order.test: one that fits Stage only, on turtlesim)
    (['move_robot', '1', '_stop_distance_m:=150'], 'parameter ~stop_distance_m = 150'),
    (['move_robot_sync', '1', '_stop_distance_m:=-0.5'], 'parameter ~stop_distance_m = -0.5'),
    # the Stage lesson's robot: bounded by a laser's reach (100 m), not turtlesim's square
    (['move_robot_sync', '1', '_stop_distance_m:=150'], 'parameter ~stop_distance_m = 150'),
    (['move_robot', '1', '_cone_half_angle_rad:=0'], 'parameter ~cone_half_angle_rad = 0'),
    (['move_robot', '1', '_cone_half_angle_rad:=4.0'], 'parameter ~cone_half_angle_rad = 4.0'),
    (['spawn_team', '_team_size:=21'], 'parameter ~team_size = 21'),
    (['spawn_team', '_team_size:=4', '_first_id:=5'], 'parameter ~first_id = 5'),
]


class TestBadArgs(unittest.TestCase):
    """Each bad command line exits 1 with a message a student can act on."""

    def test_bad_command_lines(self):
        # A node name of its own per case: private parameters stay on the parameter server.
        check_refused(self, [(['rosrun', 'multi_sync', *args, '__name:=bad_%d' % k], expected)
                             for k, (args, expected) in enumerate(CASES)], timeout_s=60.0)


if __name__ == '__main__':
    rospy.init_node('test_bad_args')
    rostest.rosrun('multi_sync', 'bad_args', TestBadArgs, sys.argv)
