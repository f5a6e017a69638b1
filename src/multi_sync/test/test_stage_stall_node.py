#!/usr/bin/env python3
"""rostest node: with the bumper and the gap off, the robots behave as the lesson's on Stage.

multi_sync.launch stop_distance_m:=0 min_gap_m:=0: after GO every robot drives straight on
at 0.2 m/s until Stage stalls it, the front pair at the wall after 1.74 m, the back pair
against the front pair's backs after 3.36 m (as real Stage 4.3.0 does on this world:
stage_multi's golden capture; on the lesson's own map real Stage gives 1.78 m and 3.40 m).
Stalled: the ground truth stands still while odom's twist still reads the commanded 0.2 and
the robot still commands 0.2.
"""
import sys

import rospy
import rostest
from course_common.testing import wait_for
from stage_watch import (
    AHEAD_OF,
    LESSON_STARTS,
    POSE_TOL_M,
    LessonTestCase,
    StageWatch,
    body_gap_m,
)

STARTUP_S = 90.0
EVENT_S = 30.0
DRIVE_S = 120.0  # 17 s of sim time at real time to the back pair's stall, on a loaded machine
SPEED_MPS = 0.2  # the lesson's; exact as a double on the wire
# Where Stage stalls them on the workspace's floor plan (stage_lite's test_stage_golden.py
# has the same from the model): deterministic, poses advance in whole 2 cm steps.
STALL_TRAVEL_M = {0: 1.74, 1: 3.36, 2: 1.74, 3: 3.36}
STALL_TOL_M = 0.021  # one 2 cm step, plus float noise
# Stalled against a back: Stage refuses a step that brings two bodies within one 2 cm cell,
# so they stop 3 cm apart (as on real Stage); less than two steps is "against it".
CONTACT_GAP_M = 0.04


class TestStageStall(LessonTestCase):
    """roslaunch multi_sync multi_sync.launch stop_distance_m:=0 min_gap_m:=0, then the
    monitor."""

    def test_robots_stall_as_the_lessons(self):
        watch = StageWatch()
        self.addCleanup(watch.close)
        self.wait_team_waiting(watch, STARTUP_S)
        for i in watch.ids():
            config = [t for t in self.robot_texts(i) if 'MoveRobotConfig' in t]
            self.assertEqual(len(config), 1, self.robot_texts(i))
            self.assertIn('stop_distance_m=0.0', config[0])
            self.assertIn('min_gap_m=0.0', config[0])

        self.start_monitor()
        wait_for(watch.gos, STARTUP_S, "the monitor's GO")
        wait_for(watch.moved, EVENT_S, 'every robot to drive off after GO')
        for i in watch.ids():
            wait_for(lambda i=i: watch.stalled(i), DRIVE_S, 'robot_%d to stall' % i)

        for i in watch.ids():
            x, y, yaw = watch.pose(i)
            self.assertAlmostEqual(x - LESSON_STARTS[i][0], STALL_TRAVEL_M[i],
                                   delta=STALL_TOL_M, msg='robot_%d stalled at x = %.3f'
                                   % (i, x))
            self.assertAlmostEqual(y, LESSON_STARTS[i][1], delta=POSE_TOL_M)
            self.assertAlmostEqual(yaw, 0.0, delta=POSE_TOL_M)
            self.assertEqual(watch.odom_speed(i), SPEED_MPS, 'robot_%d: odom twist' % i)
            self.assertEqual(watch.last_cmd(i), SPEED_MPS, 'robot_%d: last command' % i)
            self.assertEqual(len(watch.stall_runs(i)), 1,
                             'robot_%d stalled more than once' % i)
        for back, front in AHEAD_OF.items():
            gap = body_gap_m(watch.x(front), watch.x(back))
            self.assertTrue(0.0 < gap < CONTACT_GAP_M, 'robot_%d to robot_%d: %.3f m'
                            % (back, front, gap))
        for i in watch.ids():
            texts = self.robot_texts(i)
            self.assertEqual([t for t in texts if t.endswith(('stopping', 'waiting'))], [],
                             'robot_%d: the bumper or the gap stopped it' % i)
        self.assertEqual(len(watch.gos()), 1, 'one GO, heard by every robot')


if __name__ == '__main__':
    rospy.init_node('test_stage_stall')
    rostest.rosrun('multi_sync', 'stage_stall', TestStageStall, sys.argv)
