#!/usr/bin/env python3
"""rostest node: the monitor's GO reaches every robot that reads as the lesson's robots do.

The lesson's robots (lesson_robot.py) read team_status through a queue of one message once a
second. A GO that overtakes the last teammate's ready on its way to a robot is replaced in
that queue by the ready, and the robot waits forever (in one run of five with a GO sent at
once). Twenty runs in a row, each with a new monitor (started first, as the lesson says) and
four robots started together: every robot must say "Team is ready" in every run. Two runs go
side by side, each team in a namespace of its own (the load they put on each other only makes
the race likelier).
"""
import os
import sys
import unittest

import rospy
import rostest
from course_common.processes import ChildProcess
from course_common.testing import wait_for
from course_common.waiting import WaitError
from team_watch import NodeProcess

RUNS = 20
TEAMS = 2        # teams side by side, each in a namespace of its own: 10 rounds of 2 runs
TEAM = 4
START_S = 60.0   # a monitor and four robots starting on a loaded 2-core machine
GO_S = 30.0      # from the robots' start to every robot's "Team is ready" (about 3 s)
LESSON_ROBOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lesson_robot.py')


class TestLessonRobotsGo(unittest.TestCase):

    def setUp(self):
        self.procs = []

    def tearDown(self):
        self._stop_all()

    def _stop_all(self):
        for proc in self.procs:      # Ctrl-C to all at once, then wait for each
            proc.interrupt()
        while self.procs:
            self.procs.pop().stop()

    def _start(self, proc):
        self.procs.append(proc)
        return proc

    def _start_team(self, run):
        """A monitor (first, as the lesson says), then four lesson robots together, in the
        namespace /run<run>; returns (monitor, robots)."""
        env = {'ROS_NAMESPACE': 'run%d' % run}
        monitor = self._start(NodeProcess('monitor', str(TEAM), env=env))
        wait_for(lambda: monitor.printed('Waiting for robots to connect...'), START_S,
                 'run %d: the monitor to start' % run)
        robots = [self._start(ChildProcess([sys.executable, LESSON_ROBOT, str(i), str(TEAM)],
                                           env=env).start()) for i in range(TEAM)]
        return monitor, robots

    def _check_team(self, run, monitor, robots):
        try:
            wait_for(lambda: monitor.printed('All robots GO!'), START_S,
                     'run %d: the monitor to say GO' % run)
        except WaitError as err:
            self.fail('%s: monitor %s; robots %s' % (err, monitor.lines(),
                                                     [r.lines()[-3:] for r in robots]))

        def waiting():
            return [i for i, r in enumerate(robots)
                    if not r.printed("Robot %d: Team is ready. Let's move!" % i)]
        try:
            wait_for(lambda: not waiting(), GO_S, 'run %d: every robot to read GO' % run)
        except WaitError as err:
            self.fail('%s: robots %s still wait for the team; monitor: %s'
                      % (err, waiting(), monitor.lines()))

    def test_every_lesson_robot_gets_go_in_twenty_runs(self):
        for first in range(0, RUNS, TEAMS):
            teams = {run: self._start_team(run) for run in range(first, first + TEAMS)}
            for run, (monitor, robots) in teams.items():
                self._check_team(run, monitor, robots)
            self._stop_all()


if __name__ == '__main__':
    rospy.init_node('test_lesson_robots_go')
    rostest.rosrun('multi_sync', 'lesson_robots_go', TestLessonRobotsGo, sys.argv)
