#!/usr/bin/env python3
"""rostest node: the lesson run end to end (monitor started by hand after the robots)."""
import math
import sys
import unittest

import rospy
import rostest
from course_common.arena import WORLD_SIZE_M
from course_common.testing import wait_for
from multi_sync.motion import team_layout
from team_watch import NodeProcess, TeamWatch

# Generous deadlines: 20 Python nodes start slowly on a loaded 2-core machine.
STARTUP_S = 90.0
DRIVE_S = 60.0
TEAM_SIZE = 4


class TestLesson(unittest.TestCase):
    """rosrun multi_sync monitor N after roslaunch multi_sync multi_sync_turtlesim.launch."""

    def test_lesson(self):
        n = TEAM_SIZE
        watch = TeamWatch(n)
        wait_for(watch.have_poses, STARTUP_S, 'a pose from each of the %d robots' % n)
        # Twice: each robot has been waiting at least one announce period.
        wait_for(lambda: watch.announced(2), STARTUP_S, 'every robot to announce ready twice')

        with watch.lock:
            self.assertEqual(watch.first_move_wall, {}, 'a robot moved before GO')
            self.assertEqual(watch.go_msgs, [], 'GO before the monitor started')
            poses = dict(watch.pose)
        for i, (x, y, theta) in enumerate(team_layout(n)):
            self.assertAlmostEqual(poses[i][0], x, delta=1e-3, msg='robot_%d x' % i)
            self.assertAlmostEqual(poses[i][1], y, delta=1e-3, msg='robot_%d y' % i)
            self.assertAlmostEqual(poses[i][2], theta, delta=1e-3, msg='robot_%d theta' % i)
        # (The one-off 'published ready status' line may precede our /rosout subscription;
        # test_start_order_node.py reads it from the robots' own output.)
        wait_for(lambda: all(watch.logged('Robot %d: waiting for team' % i) for i in watch.ids()),
                 10.0, "every robot's 'waiting for team' log line")

        monitor = NodeProcess('monitor', str(n))
        try:
            wait_for(watch.go_count, STARTUP_S, "the monitor's GO")
            wait_for(watch.moved, DRIVE_S, 'every robot to move after GO')
            with watch.lock:
                go_wall, go = watch.go_msgs[0]
                first_moves = dict(watch.first_move_wall)
            self.assertEqual(go.header.frame_id, 'monitor')
            # The stamp is the monitor's clock at GO: recent, not zero.
            self.assertLess(abs(go.header.stamp.to_sec() - go_wall), 5.0)
            for i, t in first_moves.items():
                self.assertGreaterEqual(t, go_wall - 0.5, 'robot %d moved before GO' % i)
            # The monitor's terminal, as the student sees it (its first lines may be logged
            # before its /rosout connection is up, so they are read from its output).
            wait_for(lambda: monitor.printed('All robots GO!'), 10.0, 'the GO log line')
            for i in watch.ids():
                self.assertTrue(monitor.printed('Robot %d is ready!' % i), monitor.lines())
            # Logged just after the first command, so it may trail the command a little.
            wait_for(lambda: all(watch.logged("Robot %d: Team is ready. Let's move!" % i)
                                 for i in watch.ids()), 10.0, "every robot's 'Let's move!'")
            self.assertEqual(watch.go_count(), 1, 'one GO, heard by every robot')
            self.assertTrue(monitor.printed('Waiting for robots to connect...'))

            wait_for(watch.stopped, DRIVE_S, 'every robot to stop')
            # Stopped for good: wait until poses have settled (two reads 0.3 s apart agree).
            wait_for(lambda: self._settled(watch), 10.0, 'the robots to stand still')
            with watch.lock:
                final = dict(watch.pose)
                start = dict(watch.first_pose)
                shared = set(watch.position_ids)
            for i in watch.ids():
                x, y, _ = final[i]
                self.assertGreater(x, start[i][0] + 0.5, 'robot_%d did not drive forward' % i)
                self.assertLess(x, WORLD_SIZE_M - 0.1, 'robot_%d reached the wall' % i)
            for i in watch.ids():
                for j in watch.ids():
                    if i < j:
                        d = math.hypot(final[i][0] - final[j][0], final[i][1] - final[j][1])
                        self.assertGreater(d, 0.5, 'robots %d and %d collided' % (i, j))
            self.assertEqual(shared, set(watch.ids()), 'positions shared on team_positions')
            self.assertFalse(any(m.startswith('Oh no! I hit the wall!') for _, m in watch.logs))
            if n > 1:
                self.assertTrue(any('nearest teammate is robot' in m for _, m in watch.logs))
        finally:
            self.assertEqual(monitor.stop(), 0, '\n'.join(monitor.lines()))
            watch.close()

    def _settled(self, watch):
        with watch.lock:
            before = dict(watch.pose)
        rospy.sleep(0.3)  # the interval being compared, not a guess at readiness
        with watch.lock:
            after = dict(watch.pose)
        return all(math.hypot(after[i][0] - before[i][0], after[i][1] - before[i][1]) < 1e-6
                   for i in before)


if __name__ == '__main__':
    rospy.init_node('test_lesson')
    TEAM_SIZE = rospy.get_param('~team_size', TEAM_SIZE)
    rostest.rosrun('multi_sync', 'lesson_%d_robots' % TEAM_SIZE, TestLesson, sys.argv)
