#!/usr/bin/env python3
"""rostest node: move_robot's bad argv gives the lesson's message and exit 1, no traceback."""
import unittest

import rospy
import rostest
from course_common.testing import check_refused

MISSING = 'You must specify robot id.'
RANGE = "The robot's ID must be an integer number between 0 and 19"
CASES = [
    # (arguments after rosrun stage_multi move_robot, the lesson's message)
    ([], MISSING),
    (['20'], RANGE),
    (['-1'], RANGE),
    (['one'], RANGE),
    (['1.0'], RANGE),
]


class TestMoveRobotArgs(unittest.TestCase):
    """Each bad command line: the lesson's message, exit 1, no traceback."""

    def test_bad_command_lines(self):
        check_refused(self, [(['rosrun', 'stage_multi', 'move_robot', *args], expected)
                             for args, expected in CASES])


if __name__ == '__main__':
    rospy.init_node('test_move_robot_args')
    rostest.rosrun('stage_multi', 'move_robot_args', TestMoveRobotArgs)
