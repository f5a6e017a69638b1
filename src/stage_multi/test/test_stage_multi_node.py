#!/usr/bin/env python3
"""rostest node: stage_multi.launch as a student sees it, through ROS only.

The four robots start at the lesson's poses, each move_robot commands 0.2 m/s on its
robot_<N>/cmd_vel at 10 Hz, every robot drives off along +x, and Stage stalls them: the front
pair at the hall's wall, the back pair against the front pair's backs (ground truth stands
still while odom's twist still reads the commanded 0.2). A move_robot that is killed, or
stopped with Ctrl-C, sends one zero Twist as it exits.
"""
import os
import time
import unittest

import rosnode
import rospy
import rostest
from course_common.testing import (
    EVENT_DEADLINE_S,
    START_DEADLINE_S,
    results_dir,
    spawn,
    wait_for,
)
from course_common.testing.master import kill_node, publisher_has_connected
from course_common.testing.recorders import Recorder
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from stage_multi import lesson_world

# The lesson's world: robot_N's start (x, y), all facing +x.
STARTS = lesson_world.STARTS
ROBOTS = range(len(STARTS))
FRONT, BACK = (0, 2), (1, 3)
SPEED_MPS = 0.2  # the lesson's linear.x; exact as a double on the wire
RATE_HZ = 10.0
# Where real Stage 4.3.0 stalls them on the workspace's floor plan (the golden capture
# stage_lite's test_stage_golden.py replays); on the lesson's own map real Stage gives 1.78
# and 3.40.
STALL_TRAVEL_M = {0: 1.74, 1: 3.36, 2: 1.74, 3: 3.36}
STEP_M = 0.02  # 0.2 m/s for one 100 ms step: poses advance in whole steps
STALL_TOL_M = STEP_M / 4  # the stall is at a whole step
POSE_TOL_M = 1e-6  # y and heading: only float noise
BODY_FRONT_M, BODY_BACK_M = 0.125, 0.225  # the erratic's footprint about its pose (origin -0.05)
DRIVE_OFF_M = 0.2  # this far along +x: the robot is driving
# Ground-truth messages (2 s of sim time) at one pose while commanded: stalled for good, not a
# robot that has not started yet (the drive-off comes first) or one slow step.
STALL_STEPS = 20
RATE_MESSAGES = 30  # cmd_vel messages timed for the rate (3 s at 10 Hz)
RATE_BAND_HZ = (5.0, 20.0)  # wall-clock timing on a loaded machine: 10 Hz, not 1 or 100
# Deadlines, generous for a loaded 2-core machine (they cost time only on failure): stageros
# and four Python nodes starting; 17 s of sim time at real time to the back pair's stall.
LAUNCH_DEADLINE_S = 60.0
STALL_DEADLINE_S = 120.0
SPARE_NS = 'spare'  # a move_robot of the test's own, away from the lesson's robots


def _x(msg):
    return msg.pose.pose.position.x


def _pose2d(msg):
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    return p.x, p.y, q.z, q.w


class TestStageMulti(unittest.TestCase):
    """roslaunch stage_multi stage_multi.launch gui:=false, watched from the outside."""

    @classmethod
    def setUpClass(cls):
        # Subscribed before stageros's first step if possible; a later first message is
        # allowed for in test_lesson_run.
        cls.truth = [Recorder('/robot_%d/base_pose_ground_truth' % n, Odometry) for n in ROBOTS]
        cls.odom = [Recorder('/robot_%d/odom' % n, Odometry, keep=1) for n in ROBOTS]
        cls.cmd = [Recorder('/robot_%d/cmd_vel' % n, Twist) for n in ROBOTS]

    def test_lesson_run(self):
        """In the order a student watches it: start, commands, drive, stall, a kill."""
        self._check_start_poses()
        self._check_commands()
        self._check_drive_off()
        finals = self._check_stalls()
        self._check_rosnode_kill_stops_robot_0(finals)

    def _check_start_poses(self):
        for n in ROBOTS:
            first = wait_for(lambda n=n: self.truth[n].messages()[:1], LAUNCH_DEADLINE_S,
                             'the first ground truth of robot_%d' % n)[0]
            x0, y0 = STARTS[n]
            sim_s = first.header.stamp.to_sec()
            # At most sim_s of driving may come before the first message this test heard.
            self.assertGreaterEqual(_x(first), x0 - POSE_TOL_M, 'robot_%d x' % n)
            self.assertLessEqual(_x(first), x0 + SPEED_MPS * sim_s + POSE_TOL_M,
                                 'robot_%d x at %.1f s' % (n, sim_s))
            self.assertAlmostEqual(first.pose.pose.position.y, y0, delta=POSE_TOL_M)
            self.assertAlmostEqual(first.pose.pose.orientation.w, 1.0, delta=POSE_TOL_M)
            self.assertEqual(first.header.frame_id, '/robot_%d/odom' % n)

    def _check_commands(self):
        forward = Twist()
        forward.linear.x = SPEED_MPS
        for n in ROBOTS:
            node = '/move_robot_%d' % n
            first = wait_for(lambda n=n, node=node: self.cmd[n].messages(node)[:1],
                             LAUNCH_DEADLINE_S, 'a command from %s' % node)[0]
            self.assertEqual(first, forward, '%s: the lesson\'s Twist' % node)
            self.assertEqual(self.cmd[n].publishers(), [node], 'who commands robot_%d' % n)
            # 10 Hz: RATE_MESSAGES more messages, timed on this side (wall clock).
            start = self.cmd[n].count()
            began = time.monotonic()
            wait_for(lambda n=n, start=start: self.cmd[n].count() >= start + RATE_MESSAGES,
                     EVENT_DEADLINE_S + RATE_MESSAGES / RATE_BAND_HZ[0],
                     '%d commands from %s' % (RATE_MESSAGES, node))
            rate_hz = RATE_MESSAGES / (time.monotonic() - began)
            self.assertTrue(RATE_BAND_HZ[0] <= rate_hz <= RATE_BAND_HZ[1],
                            '%s publishes at %.1f Hz' % (node, rate_hz))
            self.assertEqual(self.cmd[n].messages()[start:start + RATE_MESSAGES],
                             [forward] * RATE_MESSAGES)

    def _check_drive_off(self):
        for n in ROBOTS:
            x0, y0 = STARTS[n]
            self.truth[n].wait_latest(lambda m, x0=x0: _x(m) > x0 + DRIVE_OFF_M,
                                      'robot_%d %.1f m along +x' % (n, DRIVE_OFF_M),
                                      LAUNCH_DEADLINE_S)
        for n in ROBOTS:
            # Straight along +x from the start: y and heading never changed, x never fell.
            msgs = self.truth[n].messages()
            self.assertTrue(all(abs(m.pose.pose.position.y - STARTS[n][1]) <= POSE_TOL_M
                                and abs(m.pose.pose.orientation.w - 1.0) <= POSE_TOL_M
                                for m in msgs), 'robot_%d left its lane' % n)
            xs = [_x(m) for m in msgs]
            self.assertEqual(xs, sorted(xs), 'robot_%d moved backwards' % n)

    def _stalled(self, n):
        """robot_n's last STALL_STEPS ground truths at one pose while odom reads 0.2 m/s."""
        last = self.truth[n].messages()[-STALL_STEPS:]
        odom = self.odom[n].latest()
        if len(last) < STALL_STEPS or odom is None or odom.twist.twist.linear.x != SPEED_MPS:
            return None
        poses = {_pose2d(m) for m in last}
        return last[-1] if len(poses) == 1 else None

    def _check_stalls(self):
        finals = {}
        for n in list(FRONT) + list(BACK):
            finals[n] = wait_for(lambda n=n: self._stalled(n), STALL_DEADLINE_S,
                                 'robot_%d stalled (ground truth still, odom at 0.2 m/s)' % n)
        travel = {n: _x(finals[n]) - STARTS[n][0] for n in ROBOTS}
        self._report(travel)
        for n in ROBOTS:
            self.assertAlmostEqual(travel[n], STALL_TRAVEL_M[n], delta=STALL_TOL_M,
                                   msg='robot_%d stalled after %.3f m' % (n, travel[n]))
            self.assertEqual(finals[n].twist.twist.linear.x, 0.0,
                             'robot_%d: ground truth twist while stalled' % n)
        for front, back in zip(FRONT, BACK, strict=True):
            gap = (_x(finals[front]) - BODY_BACK_M) - (_x(finals[back]) + BODY_FRONT_M)
            # one 2 cm collision cell apart (3 cm on the real Stage too)
            self.assertTrue(STEP_M - POSE_TOL_M <= gap < 2 * STEP_M,
                            'robot_%d stopped %.3f m behind robot_%d' % (back, gap, front))
        return finals

    def _report(self, travel):
        text = ''.join('robot_%d stalled after %.3f m\n' % (n, travel[n]) for n in ROBOTS)
        rospy.loginfo('stall distances:\n%s', text)
        with open(os.path.join(results_dir(), 'stage_multi_stalls.txt'), 'w') as f:
            f.write(text)

    def _check_rosnode_kill_stops_robot_0(self, finals):
        # The watchdog cannot stop robot_0 here: robots 1-3 keep commanding, and stageros's
        # watchdog time is shared. Only move_robot_0's zero Twist can.
        node = '/move_robot_0'
        before = self.cmd[0].count()
        kill_node(node)
        wait_for(lambda: node not in rosnode.get_node_names(), EVENT_DEADLINE_S,
                 '%s to unregister' % node)
        wait_for(lambda: self.cmd[0].count() > before and self.cmd[0].latest() == Twist(),
                 EVENT_DEADLINE_S, 'the zero Twist from the killed %s' % node)
        self.odom[0].wait_latest(lambda m: m.twist.twist.linear.x == 0.0,
                                 'robot_0 commanded to stop', EVENT_DEADLINE_S)
        stops = [m for m in self.cmd[0].messages()[before:] if m == Twist()]
        self.assertEqual(len(stops), 1, 'one zero Twist as it exits')
        self.assertEqual(self.cmd[0].messages()[-1], Twist(), 'nothing after the stop')
        self.assertEqual(self.odom[1].latest().twist.twist.linear.x, SPEED_MPS,
                         'robot_1 still commanded')
        self.assertEqual(_pose2d(self.truth[0].latest()), _pose2d(finals[0]))

    def test_ctrl_c_sends_one_zero_twist(self):
        # A move_robot of the test's own, in a namespace: the topic is relative.
        topic = '/%s/robot_3/cmd_vel' % SPARE_NS
        node = '/%s/move_robot_3' % SPARE_NS
        cmd = Recorder(topic, Twist)
        self.addCleanup(cmd.close)
        tool = spawn(['rosrun', 'stage_multi', 'move_robot', '3', '__ns:=' + SPARE_NS])
        self.addCleanup(tool.stop)
        line = tool.wait_line('Robot 3: moving forward', START_DEADLINE_S)
        self.assertIn('0.2 m/s on %s' % topic, line)
        wait_for(lambda: publisher_has_connected(node, topic), START_DEADLINE_S,
                 '%s connected to this test' % node)
        cmd.wait(lambda m: m.linear.x == SPEED_MPS, 'a forward command on %s' % topic)
        tool.interrupt()
        self.assertEqual(tool.wait_exit(EVENT_DEADLINE_S), 0, tool.output())
        self.assertNotIn('Traceback', tool.output())
        wait_for(lambda: cmd.latest() == Twist(), EVENT_DEADLINE_S,
                 'the zero Twist after Ctrl-C')
        msgs = cmd.messages()
        self.assertEqual(cmd.publishers(), [node])
        self.assertEqual(msgs.count(Twist()), 1, 'one zero Twist as it exits')
        forward = Twist()
        forward.linear.x = SPEED_MPS
        self.assertEqual(msgs[:-1], [forward] * (len(msgs) - 1))


if __name__ == '__main__':
    rospy.init_node('test_stage_multi')
    rostest.rosrun('stage_multi', 'stage_multi', TestStageMulti)
