#!/usr/bin/env python3
"""turtlesim_node motion conformance: the worked trajectory, rates, the wrap, the timeout."""

import math
import re
import time

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, wait_for
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from sim_support import DEFAULT_BG, DEFAULT_PEN, SimTestCase, wait_connected
from turtle_lite.testing import CENTER, POSE_TOL, WORLD, PoseRecorder

WALL_RE = re.compile(r'^Oh no! I hit the wall! \(Clamping from \[x=(-?\d+\.\d{6}), '
                     r'y=(-?\d+\.\d{6})\]\)$')


def twist(vx=0.0, vy=0.0, w=0.0):
    msg = Twist()
    msg.linear.x = vx
    msg.linear.y = vy
    msg.angular.z = w
    return msg


class SimMotionTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.cmd = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
        wait_connected(cls.cmd, 'turtlesim to subscribe /turtle1/cmd_vel')

    def setUp(self):
        self.reset()
        self.pose.wait(lambda p: abs(p.x - CENTER) < POSE_TOL and p.linear_velocity == 0,
                       'turtle1 back at the centre')

    def wall_lines(self):
        return [line for line in self.logs.lines(Log.WARN) if line.startswith('Oh no!')]

    def wait_logs_delivered(self):
        """Waits until every line the simulator logged so far has reached this test.

        /clear logs "Clearing turtlesim." through the same /rosout publisher and connection as
        every earlier line, which arrive in order: once it is here, so are they.
        """
        def clearing():
            return self.logs.lines(Log.INFO).count('Clearing turtlesim.')
        seen = clearing()
        self.clear()
        wait_for(lambda: clearing() > seen, EVENT_DEADLINE_S,
                 'the simulator\'s "Clearing turtlesim." line, after its earlier lines')

    def test_worked_trajectory_rate_and_heading_first(self):
        """Items 1 and 2: dt = 0.016 s, 62.5 Hz, theta_k = 0.008 k, x/y to 1e-6."""
        start = self.pose.wait_count(40, 'idle poses')
        stamps_before = len(start)
        t0 = time.monotonic()
        self.pose.wait_count(125, '125 idle poses')
        idle_rate = (self.pose.count() - stamps_before) / (time.monotonic() - t0)
        self.assertAlmostEqual(idle_rate, 62.5, delta=62.5 * 0.1, msg='pose rate when idle')

        self.absolute(5.544445, 5.544445, 0.0)
        self.pose.wait(lambda p: p.x == self.pose.latest().x and p.theta == 0.0, 'teleport')
        self.pose.clear()
        rate = rospy.Rate(50)
        for _ in range(150):
            self.cmd.publish(twist(1.0, 0.0, 0.5))
            rate.sleep()
        self.pose.wait_at_rest()
        moving = [p for p in self.pose.messages() if p.linear_velocity > 0]
        self.assertGreater(len(moving), 200)
        # turtlesim: 249 ticks (187 while commands flow + 62 of timeout coast).
        self.assertAlmostEqual(len(moving), 249, delta=12)
        x0 = 5.544445
        y0 = 5.544445
        for p in moving:
            k = round(p.theta / 0.008)
            self.assertAlmostEqual(p.theta, 0.008 * k, delta=2e-6)
            xk = x0 + 0.016 * sum(math.cos(0.008 * i) for i in range(1, k + 1))
            yk = y0 + 0.016 * sum(math.sin(0.008 * i) for i in range(1, k + 1))
            self.assertAlmostEqual(p.x, xk, delta=2e-6, msg='tick %d' % k)
            self.assertAlmostEqual(p.y, yk, delta=2e-6, msg='tick %d' % k)
        ks = [round(p.theta / 0.008) for p in moving]
        self.assertEqual(ks, list(range(1, len(moving) + 1)), 'one pose per tick, none lost')

    def test_wrap_uses_truncated_pi(self):
        """Item 3."""
        for theta, expected in ((math.pi, -3.1415925), (-math.pi, 3.1415925),
                                (3.5, -2.7831852)):
            self.absolute(3.0, 3.0, theta)
            pose = self.pose.wait(lambda p, e=expected: abs(p.theta - e) < 1e-6,
                                  'theta %r wrapped to %r' % (theta, expected))
            self.assertAlmostEqual(pose.theta, expected, delta=2e-7)
        self.spawn(2.0, 2.0, 7.0, 'wrap7')
        wrap7 = PoseRecorder('/wrap7/pose')
        self.addCleanup(wrap7.close)
        pose = wrap7.wait(lambda p: True, 'a pose of wrap7')
        self.assertAlmostEqual(pose.theta, 0.7168147, delta=2e-7)

    def test_timeout_hypot_and_velocities(self):
        """Items 4 and 5."""
        self.pose.clear()
        self.cmd.publish(twist(-1.0, 0.0, -0.5))
        self.pose.wait(lambda p: p.linear_velocity > 0, 'the command applied')
        self.pose.wait_at_rest()
        poses = self.pose.messages()
        moving = [p for p in poses if p.linear_velocity > 0]
        self.assertAlmostEqual(len(moving), 62.5, delta=4)  # 1 s of 16 ms ticks
        self.assertTrue(all(p.linear_velocity == 1.0 for p in moving), 'hypot is >= 0')
        self.assertTrue(all(p.angular_velocity == -0.5 for p in moving), 'w is signed')
        first_rest = poses.index(next(p for p in poses[poses.index(moving[0]):]
                                      if p.linear_velocity == 0))
        self.assertEqual(poses[first_rest].x, poses[first_rest - 1].x,
                         'velocities drop to 0 on the tick the motion stops')
        self.assertLess(moving[-1].x, CENTER, 'linear.x = -1 drives backwards')

        self.cmd.publish(twist(3.0, 4.0))
        pose = self.pose.wait(lambda p: p.linear_velocity > 0, 'the (3, 4) command')
        self.assertAlmostEqual(pose.linear_velocity, 5.0, delta=POSE_TOL)

    def test_holonomic_y_moves_left(self):
        """Item 6."""
        self.cmd.publish(twist(0.0, 1.0))
        pose = self.pose.wait(lambda p: p.y > CENTER + 0.05, 'motion to the left (+y)')
        self.assertAlmostEqual(pose.x, CENTER, delta=POSE_TOL)
        self.assertAlmostEqual(pose.theta, 0.0, delta=POSE_TOL)

    def test_walls_clamp_and_warn_with_screen_y(self):
        """Item 7."""
        self.absolute(0.1, 3.0, 0.0)
        self.pose.wait(lambda p: abs(p.x - 0.1) < POSE_TOL, 'teleport near the left wall')
        before = len(self.wall_lines())
        deadline = time.monotonic() + 0.5  # half a second of commands: the drive, not a wait
        while time.monotonic() < deadline:
            self.cmd.publish(twist(-1.0))
            time.sleep(0.05)
        pose = self.pose.wait(lambda p: p.x == 0.0, 'turtle1 pinned at x = 0')
        self.assertAlmostEqual(pose.y, 3.0, delta=POSE_TOL)
        self.assertEqual(pose.linear_velocity, 1.0, 'velocities are not zeroed at a wall')
        wait_for(lambda: len(self.wall_lines()) - before >= 10, EVENT_DEADLINE_S,
                 'one wall WARN per tick')
        for line in self.wall_lines()[before:]:
            match = WALL_RE.match(line)
            self.assertIsNotNone(match, line)
            self.assertLess(float(match.group(1)), 0.0)
            self.assertEqual(match.group(2), '%f' % (WORLD - 3.0), 'screen y = H - y')
        self.pose.wait_at_rest()
        self.wait_logs_delivered()

        # Top edge of teleport_absolute: silent clamp. Bottom edge: WARN.
        before = len(self.wall_lines())
        self.absolute(3.0, 20.0, 0.0)
        pose = self.pose.wait(lambda p: p.x == 3.0, 'teleport above the top')
        self.assertAlmostEqual(pose.y, WORLD, delta=POSE_TOL)
        self.pose.wait_count(20)
        self.assertEqual(len(self.wall_lines()), before, 'no WARN sitting on the top wall')
        self.absolute(4.0, -1.0, 0.0)
        self.logs.wait_line('Clamping from [x=4.000000, y=%f]' % (WORLD + 1.0))
        pose = self.pose.wait(lambda p: p.x == 4.0, 'teleport below the bottom')
        self.assertEqual(pose.y, 0.0)

    def test_teleports_are_queued_relative_rotates_first_and_draw(self):
        """Item 8."""
        self.color.wait_rgb(DEFAULT_BG, 'the background under a fresh turtle1')
        self.cmd.publish(twist(0.5, 0.0, 0.0))
        self.pose.wait(lambda p: p.linear_velocity == 0.5, 'moving')
        self.absolute(2.0, 2.0, 0.0)
        self.relative(1.0, math.pi / 2)
        pose = self.pose.wait(lambda p: abs(p.theta - math.pi / 2) < 1e-3, 'both teleports')
        self.assertAlmostEqual(pose.x, 2.0, delta=0.05)
        self.assertGreater(pose.y, 2.9)  # rotated first, then moved 1 m up (plus motion)
        self.assertEqual(pose.linear_velocity, 0.5, 'teleports keep the velocities')
        self.pose.wait_at_rest()
        self.absolute(8.0, 8.0, 0.0)
        self.color.wait_rgb(DEFAULT_PEN, 'the pen colour right after a teleport')


if __name__ == '__main__':
    rospy.init_node('test_sim_motion')
    rostest.rosrun('turtle_lite', 'sim_motion', SimMotionTest)
