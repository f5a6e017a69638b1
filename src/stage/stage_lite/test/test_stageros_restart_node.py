#!/usr/bin/env python3
"""Kill and restart stageros under a running cmd_vel publisher: the team picks it up again."""

import rostest
from nav_msgs.msg import Odometry
from stage_support import (
    EVENT_DEADLINE_S,
    START_DEADLINE_S,
    Recorder,
    StageTestCase,
    start_stageros,
    wait_for,
    world,
)

START_X = 1.95
MOVED_M = 0.05


class StagerosRestartTest(StageTestCase):
    NODE_NAME = 'stageros_restart_test'

    def _run_once(self, *args, env=None):
        odom = Recorder('/robot_0/odom', Odometry, keep=1)
        proc = start_stageros(*args, world('node_four_robots.world'), '_speedup:=2.0',
                              '_base_watchdog_timeout:=1.0', env=env)
        try:
            first = wait_for(odom.latest, START_DEADLINE_S, 'the first odom of a new stageros',
                             alive=proc.alive)
            self.assertLess(first.pose.pose.position.x, START_X + MOVED_M,
                            'a new stageros starts from the start pose')
            wait_for(lambda: odom.latest().pose.pose.position.x > START_X + MOVED_M,
                     EVENT_DEADLINE_S, 'robot_0 driven by the running publisher',
                     alive=proc.alive)
        finally:
            code = proc.stop()
            odom.close()
        return code, proc

    def test_kill_and_restart_under_a_running_publisher(self):
        code, proc = self._run_once(env={'DISPLAY': None})  # no -g, no display: WARN, headless
        self.assertEqual(code, 0, 'stageros ends cleanly on SIGINT')
        self.assertIn('no display', proc.output())
        code, _ = self._run_once('-g')
        self.assertEqual(code, 0)


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_restart', StagerosRestartTest)
