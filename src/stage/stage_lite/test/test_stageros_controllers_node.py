#!/usr/bin/env python3
"""stageros runs the world's controllers as the real stageros does: its watchdog (default
0.2 s) stops every robot after the controllers have set their speeds, each step, so that
without cmd_vel they move for one step only; with `_base_watchdog_timeout:=0` they drive.
A controller that raises is one ERROR line naming the world file's line, and the simulation
goes on."""
import os

import rostest
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from stage_support import (
    EVENT_DEADLINE_S,
    START_DEADLINE_S,
    Recorder,
    StageTestCase,
    start_stageros,
    wait_for,
    world,
)

CONTROLLERS = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'controllers')
WORLD = world('node_controllers.world')
ONE_STEP_M = 0.4 * 0.1          # wander's cruise speed for one interval_sim
START = {'robot_0': (0.0, 1.0), 'robot_1': (-2.0, -1.0)}
RAISED = '%s:18: ctrl "stalls_out 1.0" on mine: RuntimeError: past my time' % WORLD


def moved(msg, robot):
    x0, y0 = START[robot]
    p = msg.pose.pose.position
    return ((p.x - x0) ** 2 + (p.y - y0) ** 2) ** 0.5


class StagerosControllersTest(StageTestCase):
    NODE_NAME = 'stageros_controllers_test'

    def _run(self, *params):
        truth = {r: Recorder('/%s/base_pose_ground_truth' % r, Odometry) for r in START}
        clock = Recorder('/clock', Clock, keep=1)
        proc = start_stageros('-g', WORLD, '_speedup:=4', '__name:=stageros_%d' % len(params),
                              *params, env={'STAGEPATH': CONTROLLERS})
        self.addCleanup(proc.stop)
        for r in truth.values():
            self.addCleanup(r.close)
        self.addCleanup(clock.close)
        wait_for(clock.latest, START_DEADLINE_S, 'the first /clock', alive=proc.alive)
        return proc, truth, clock

    def _raised_once(self, proc, clock):
        wait_for(lambda: RAISED in proc.output(), EVENT_DEADLINE_S,
                 'the controller\'s ERROR line; output:\n%s' % proc.output(), alive=proc.alive)
        seen = clock.latest().clock.to_sec()
        wait_for(lambda: clock.latest().clock.to_sec() > seen + 1.0, EVENT_DEADLINE_S,
                 'the clock going on after the error', alive=proc.alive)
        self.assertEqual(proc.output().count('past my time'), 1, proc.output())
        self.assertNotIn('Traceback', proc.output())

    def test_the_default_watchdog_lets_controllers_move_one_step(self):
        proc, truth, clock = self._run()
        self._raised_once(proc, clock)     # 1 s of sim time and more have passed
        for robot, recorder in truth.items():
            late = [m for m in recorder.messages() if m.header.stamp.to_sec() >= 0.25]
            self.assertTrue(late, robot)
            for msg in late:
                self.assertAlmostEqual(moved(msg, robot), ONE_STEP_M if robot == 'robot_0'
                                       else 0.1 * 0.1, delta=1e-6, msg=robot)

    def test_without_the_watchdog_the_controllers_drive(self):
        proc, truth, clock = self._run('_base_watchdog_timeout:=0')
        wait_for(lambda: truth['robot_0'].latest() is not None
                 and moved(truth['robot_0'].latest(), 'robot_0') > 0.5, EVENT_DEADLINE_S,
                 'wander driving robot_0 half a metre', alive=proc.alive)
        self._raised_once(proc, clock)
        # its last command stays after the error: robot_1 goes on at 0.1 m/s
        end = truth['robot_1'].latest()
        self.assertAlmostEqual(moved(end, 'robot_1'),
                               0.1 * (round(end.header.stamp.to_sec() * 10) - 1) * 0.1,
                               delta=1e-6)


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_controllers', StagerosControllersTest)
