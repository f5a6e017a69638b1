#!/usr/bin/env python3
"""rostest node: the Stage lesson as taught: multi_sync.launch, then `rosrun multi_sync monitor 4`.

The robots wait at the lesson's start poses until GO, all four drive off on it, the front pair
stops short of the hall's wall (the bumper: what the laser sees) and the back pair behind
them (the shared positions), none ever stalled by Stage, and the monitor and the robots print
the lesson's lines.
"""
import re
import sys

import rospy
import rostest
from course_common.testing import info_texts, wait_for
from stage_watch import (
    AHEAD_OF,
    BACK,
    BODY_FRONT_M,
    FRONT,
    LESSON_STARTS,
    POSE_TOL_M,
    WALL_FACE_X,
    LessonTestCase,
    StageWatch,
    body_gap_m,
    laser_to_wall_m,
    lesson_line_kinds,
)

# Generous deadlines for a loaded 2-core machine (they cost time only on failure): stageros
# and four Python robots starting; ~12 s of sim time at real time to the back pair's stop.
STARTUP_S = 90.0
EVENT_S = 30.0
DRIVE_S = 120.0
STOP_DISTANCE_M = 0.5  # move_robot's default bumper distance, from the laser
MIN_GAP_M = 1.0  # move_robot's default teammate gap, between poses
BUMPER_LINE = re.compile(r'^Robot (\d+): laser: obstacle ([\d.]+) m ahead, stopping$')
GAP_LINE = re.compile(r'^Robot (\d+): robot (\d+) is ([\d.]+) m ahead, waiting$')


class TestStageLesson(LessonTestCase):
    """roslaunch multi_sync multi_sync.launch (no argument), the monitor started by hand."""

    def test_lesson(self):
        watch = StageWatch()
        self.addCleanup(watch.close)
        self.wait_team_waiting(watch, STARTUP_S)
        for i, (x0, y0) in enumerate(LESSON_STARTS):
            x, y, yaw = watch.first_pose(i)
            self.assertAlmostEqual(x, x0, delta=POSE_TOL_M, msg='robot_%d start x' % i)
            self.assertAlmostEqual(y, y0, delta=POSE_TOL_M, msg='robot_%d start y' % i)
            self.assertAlmostEqual(yaw, 0.0, delta=POSE_TOL_M, msg='robot_%d start yaw' % i)

        monitor = self.start_monitor()
        wait_for(watch.gos, STARTUP_S, "the monitor's GO")
        wait_for(watch.moved, EVENT_S, 'every robot to drive off after GO')
        for i in watch.ids():
            wait_for(lambda i=i: watch.stopped(i), DRIVE_S, 'robot_%d to stop and stand' % i)

        self._check_stops(watch)
        self._check_monitor_lines(monitor)
        self._check_robot_lines(watch)
        self.assertEqual(len(watch.gos()), 1, 'one GO, heard by every robot')
        # The monitor runs on Stage's clock: GO is stamped with sim time, once /clock runs.
        self.assertGreater(watch.gos()[0].header.stamp.to_sec(), 0.0, 'GO stamped 0')
        self.assertFalse(monitor.printed('GO sent before'), monitor.lines())

    def _check_stops(self, watch):
        poses = {i: watch.pose(i) for i in watch.ids()}
        for i in watch.ids():
            x, y, yaw = poses[i]
            self.assertEqual(watch.last_cmd(i), 0.0, 'robot_%d: last command' % i)
            self.assertEqual(watch.odom_speed(i), 0.0, 'robot_%d: odom twist' % i)
            self.assertEqual(watch.stall_runs(i), [], 'robot_%d was stalled by Stage '
                             '(steps standing while commanded)' % i)
            self.assertAlmostEqual(y, LESSON_STARTS[i][1], delta=POSE_TOL_M,
                                   msg='robot_%d left its lane' % i)
            self.assertAlmostEqual(yaw, 0.0, delta=POSE_TOL_M, msg='robot_%d turned' % i)
        for i in FRONT:
            x = poses[i][0]
            ahead = laser_to_wall_m(x)
            self.assertTrue(0.0 < ahead <= STOP_DISTANCE_M + POSE_TOL_M,
                            'robot_%d at x = %.3f: its laser %.3f m from the wall' % (i, x, ahead))
            self.assertLess(x + BODY_FRONT_M, WALL_FACE_X, 'robot_%d touches the wall' % i)
        for i in BACK:
            front, back = poses[AHEAD_OF[i]][0], poses[i][0]
            self.assertGreater(body_gap_m(front, back), 0.0,
                               'robot_%d (x = %.3f) touches robot_%d (x = %.3f)'
                               % (i, back, AHEAD_OF[i], front))
            self.assertLess(front - back, MIN_GAP_M, 'robot_%d stopped early' % i)

    def _check_monitor_lines(self, monitor):
        # Its first lines may go out before its /rosout connection is up: its own output.
        wait_for(lambda: monitor.printed('All robots GO!'), EVENT_S, "the monitor's GO line")
        texts = info_texts(monitor.lines())
        self.assertEqual(texts[0], 'Waiting for robots to connect...', monitor.lines())
        ready = [t for t in texts if t.endswith(' is ready!')]
        self.assertCountEqual(ready, ['Robot %d is ready!' % i for i in range(4)],
                              monitor.lines())
        self.assertEqual(texts.count('All robots GO!'), 1, monitor.lines())
        self.assertGreater(texts.index('All robots GO!'), texts.index(ready[-1]))

    def _check_robot_lines(self, watch):
        for i in watch.ids():
            texts = self._texts_once_moving(i)
            self.assertRegex(lesson_line_kinds(texts, i), '^PW+TF$', texts)
            stops = [(BUMPER_LINE.match(t), GAP_LINE.match(t)) for t in texts]
            bumper = [m for m, _ in stops if m and int(m.group(1)) == i]
            gap = [m for _, m in stops if m and int(m.group(1)) == i]
            if i in FRONT:
                self.assertEqual(len(bumper), 1, texts)
                self.assertLessEqual(float(bumper[0].group(2)), STOP_DISTANCE_M)
                self.assertEqual(gap, [], texts)
            else:
                self.assertEqual(bumper, [], texts)
                self.assertEqual([int(m.group(2)) for m in gap], [AHEAD_OF[i]], texts)

    def _texts_once_moving(self, i):
        """Robot i's lines once its first-move line is there ("Let's move!" and the first-move
        line are logged at the tick after the first command)."""
        def texts():
            found = self.robot_texts(i)
            return found if 'F' in lesson_line_kinds(found, i) else None
        return wait_for(texts, EVENT_S, "robot %d's first-move line" % i)


if __name__ == '__main__':
    rospy.init_node('test_stage_lesson')
    rostest.rosrun('multi_sync', 'stage_lesson', TestStageLesson, sys.argv)
