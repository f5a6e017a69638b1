#!/usr/bin/env python3
"""rostest node: move_robot's bad argv gives the lesson's message and exit 1, no traceback."""
import unittest
from concurrent.futures import ThreadPoolExecutor

import rospy
import rostest
from course_common.processes import run_to_exit
from course_common.testing import START_DEADLINE_S

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
WORKERS = 3  # each run is mostly Python start-up; leave a core to the rest of the machine


class TestMoveRobotArgs(unittest.TestCase):
    """Each bad command line: the lesson's message, exit 1, no traceback."""

    def test_bad_command_lines(self):
        def run(args):
            return run_to_exit(['rosrun', 'stage_multi', 'move_robot', *args],
                               START_DEADLINE_S)
        with ThreadPoolExecutor(max_workers=WORKERS) as pool:
            results = list(pool.map(run, [args for args, _ in CASES]))
        for (args, expected), (code, output) in zip(CASES, results, strict=True):
            with self.subTest(args=args):
                self.assertEqual(code, 1, output)
                self.assertIn(expected, output)
                self.assertNotIn('Traceback', output)


if __name__ == '__main__':
    rospy.init_node('test_move_robot_args')
    rostest.rosrun('stage_multi', 'move_robot_args', TestMoveRobotArgs)
