#!/usr/bin/env python3
"""Integration test of pioneer.launch sim:=stage: Stage's Pioneer 3-DX behind the lab's
topics, as a student sees it on /pioneer/pose: it drives and turns as commanded, by Stage's
rules; the wheels are held within the Pioneer's limits; NaN and inf commands are refused;
the room's wall stops it; the teleop's quarter-speed command (task one) drives it."""
import math
import unittest

import rospy
import rostest
from course_common.angles import yaw_from_quaternion
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, wait_for
from course_common.testing.master import publisher_has_connected, topic_types
from course_common.testing.recorders import LogRecorder, Recorder, stamp_ns
from geometry_msgs.msg import Pose2D, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from std_srvs.srv import Empty

BRIDGE = '/pioneer/stage_pioneer'
STAGE = '/pioneer/stage/stageros'
START = (5.544445, 5.544445, 0.0)  # the world file's pose of the Pioneer: the turtle's spawn
STEP_S = 0.1  # the world's interval_sim: Stage moves the robot by velocity x 0.1 s a step
STEP_NS = 100_000_000
COMMAND_HZ = 10.0  # a held key: the command again every 0.1 s (Stage stops it 1 s after)
MAX_WHEEL_MPS = 0.5  # pioneer.inc's velocity_bounds: 0.5 m/s
MAX_TURN_RADPS = math.pi / 2  # and 90 deg/s
TOL = 1e-9  # Stage's steps are sums of doubles: only rounding
# go-to-goal's top speeds (1.2 m/s, 5.236 rad/s): the right wheel asked for 2.064 m/s
GO_TO_GOAL_SCALE = MAX_WHEEL_MPS / (1.2 + 0.165 * 5.236)
FRONT_M = 0.511 / 2 - 0.04465  # the body's front, ahead of the pose (size and origin)
WALL_X_M = 499 / 45  # the east wall's inner face: the turtle world's far side
CELL_M = 0.02  # the world's resolution: a collision is decided cell by cell
DRIVE_DEADLINE_S = 40.0  # a few seconds of simulated (= wall) time, on a loaded machine
WALL_DEADLINE_S = 60.0  # 5.3 m to the wall at 0.5 m/s: 11 s, on a loaded machine


def _twist(v=0.0, w=0.0):
    twist = Twist()
    twist.linear.x, twist.angular.z = v, w
    return twist


def _pose(odom):
    """(stamp ns, x, y, yaw) of a ground-truth message."""
    p, q = odom.pose.pose.position, odom.pose.pose.orientation
    return stamp_ns(odom), p.x, p.y, yaw_from_quaternion(q.x, q.y, q.z, q.w)


def _moves(poses):
    """The steps between consecutive poses in which the robot moved: (dx, dy, dyaw) each.
    The poses must be one every step (none missed)."""
    moves = []
    for (t0, *a), (t1, *b) in zip(poses[:-1], poses[1:], strict=True):
        assert t1 - t0 == STEP_NS, 'ground truth at %d then %d ns: a step missed' % (t0, t1)
        delta = tuple(q - p for p, q in zip(a, b, strict=True))
        if any(delta):
            moves.append(delta)
    return moves


class TestPioneerStage(unittest.TestCase):
    """Each test starts from the Pioneer at rest at its start pose (reset_positions)."""

    @classmethod
    def setUpClass(cls):
        cls.truth = Recorder('/pioneer/stage/base_pose_ground_truth', Odometry)
        cls.pose2d = Recorder('/pioneer/pose', Pose2D, keep=1)
        cls.sent = Recorder('/pioneer/stage/cmd_vel', Twist)
        wait_for(lambda: cls.truth.latest() and cls.pose2d.latest(), START_DEADLINE_S,
                 'the first ground truth and /pioneer/pose')
        cls.cmd = rospy.Publisher('/pioneer/cmd_vel', Twist, queue_size=10)
        cls.teleop = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=10)
        wait_for(lambda: publisher_has_connected(rospy.get_name(), '/pioneer/cmd_vel', BRIDGE),
                 START_DEADLINE_S, 'this test connected to stage_pioneer')
        wait_for(lambda: publisher_has_connected(rospy.get_name(), '/turtle1/cmd_vel',
                                                 '/pioneer_interface'),
                 START_DEADLINE_S, 'this test connected to pioneer_interface')
        wait_for(lambda: publisher_has_connected(BRIDGE, '/pioneer/stage/cmd_vel', STAGE),
                 START_DEADLINE_S, 'stage_pioneer connected to stageros')
        rospy.wait_for_service('/pioneer/stage/reset_positions', START_DEADLINE_S)
        cls.reset = rospy.ServiceProxy('/pioneer/stage/reset_positions', Empty)
        cls.logs = LogRecorder(BRIDGE)

    def setUp(self):
        self.cmd.publish(_twist())
        self._wait_rest(rospy.Time.now().to_nsec())
        self.reset()
        self.truth.wait_latest(lambda m: _pose(m)[1:] == START, 'the Pioneer back at its start')
        self.pose2d.wait_latest(lambda p: (p.x, p.y, p.theta) == START,
                                'the Pose2D of the start')
        self.truth.clear()
        self.sent.clear()
        # the record starts with a pose at the start: the first step of a drive shows in it
        self.truth.wait_count(1, 'a ground truth at the start')

    def _first_sent(self, what):
        """The first command sent to Stage since setUp (which clears the record before the
        test publishes, so a fast answer cannot be missed)."""
        return wait_for(self.sent.messages, EVENT_DEADLINE_S, what)[0]

    def _wait_rest(self, after_ns):
        """The ground-truth poses once two consecutive ones, both stamped a step or more
        after after_ns, are the same: the robot at rest."""
        def resting():
            poses = [_pose(m) for m in self.truth.messages()]
            last = [p for p in poses if p[0] >= after_ns + STEP_NS][-2:]
            return poses if len(last) == 2 and last[0][1:] == last[1][1:] else None
        return wait_for(resting, DRIVE_DEADLINE_S, 'the Pioneer at rest')

    def _hold(self, twist, done, what, deadline_s=DRIVE_DEADLINE_S):
        """Sends twist every 0.1 s of simulated time, as a held key, until done(); then one
        zero Twist. Returns the simulated time (ns) of that last command."""
        rate = rospy.Rate(COMMAND_HZ)
        wait_for(lambda: self.cmd.publish(twist) or rate.sleep() or done(), deadline_s, what)
        self.cmd.publish(_twist())
        return rospy.Time.now().to_nsec()

    def _drive_for(self, twist, duration_s):
        """Holds twist for duration_s of simulated time; returns (the ground truth until the
        robot is at rest again, the moving steps, the simulated time it was commanded)."""
        start = rospy.get_time()
        stop_ns = self._hold(twist, lambda: rospy.get_time() - start >= duration_s,
                             'driving for %g s of simulated time' % duration_s)
        poses = self._wait_rest(stop_ns)
        return poses, _moves(poses), stop_ns / 1e9 - start

    def _assert_pose2d_is_truth(self, poses):
        got = self.pose2d.wait_latest(
            lambda p: abs(p.x - poses[-1][1]) < TOL and abs(p.y - poses[-1][2]) < TOL,
            'the Pose2D of the resting robot')
        self.assertAlmostEqual(got.theta, poses[-1][3], delta=TOL)

    def test_graph_is_the_labs(self):
        types = topic_types()
        self.assertEqual(types['/pioneer/pose'], 'geometry_msgs/Pose2D')
        self.assertEqual(types['/pioneer/cmd_vel'], 'geometry_msgs/Twist')
        self.assertEqual(types['/pioneer/stage/cmd_vel'], 'geometry_msgs/Twist')
        self.assertEqual(types['/pioneer/stage/base_pose_ground_truth'], 'nav_msgs/Odometry')
        self.assertNotIn('/pioneer/turtle_pose', types, 'no turtle on Stage')
        self.assertTrue(rospy.get_param('/use_sim_time'))

    def test_forward_v_for_t_advances_v_t(self):
        v, duration = 0.3, 2.0
        poses, moves, commanded = self._drive_for(_twist(v), duration)
        # Stage's rule: v x 0.1 s along the heading each step, for every step it is commanded
        for dx, dy, dyaw in moves:
            self.assertAlmostEqual(dx, v * STEP_S, delta=TOL)
            self.assertEqual((dy, dyaw), (0.0, 0.0))
        moved_s = len(moves) * STEP_S
        self.assertAlmostEqual(poses[-1][1] - START[0], v * moved_s, delta=TOL)
        # it moves for the time it was commanded, give or take the step a command waits for
        self.assertLessEqual(abs(moved_s - commanded), 2 * STEP_S + TOL,
                             'moved %.1f s, commanded %.2f s' % (moved_s, commanded))
        self.assertGreaterEqual(moved_s, duration - STEP_S)
        self._assert_pose2d_is_truth(poses)

    def test_pure_turn_changes_theta_only(self):
        w, duration = 0.5, 1.5
        poses, moves, commanded = self._drive_for(_twist(0.0, w), duration)
        moved_s = len(moves) * STEP_S
        self.assertGreaterEqual(moved_s, duration - STEP_S)
        self.assertLessEqual(abs(moved_s - commanded), 2 * STEP_S + TOL)
        # the turn goes through the wheels (vLeft = -vRight = 0.0825 m/s) and back: w again
        for dx, dy, dyaw in moves:
            self.assertEqual((dx, dy), (0.0, 0.0), 'a turn on the spot moves nothing')
            self.assertAlmostEqual(dyaw, w * STEP_S, delta=TOL)
        self.assertAlmostEqual(poses[-1][3], w * moved_s, delta=TOL)
        self._assert_pose2d_is_truth(poses)

    def test_wheel_speeds_are_held_within_the_limits(self):
        cases = [
            # (command, what Stage is sent): straight on at 2 m/s -> each wheel at 0.5 m/s
            ((2.0, 0.0), (MAX_WHEEL_MPS, 0.0)),
            # a turn of 3 rad/s on the spot: wheels at +-0.495 m/s, the turn held to 90 deg/s
            ((0.0, -3.0), (0.0, -MAX_TURN_RADPS)),
            # go-to-goal's top speeds: both scaled by one factor (0.5 / 2.064), the arc kept
            ((1.2, 5.236), (1.2 * GO_TO_GOAL_SCALE, 5.236 * GO_TO_GOAL_SCALE)),
        ]
        for (v, w), (sent_v, sent_w) in cases:
            with self.subTest(command=(v, w)):
                self.setUp()
                poses, moves, _ = self._drive_for(_twist(v, w), 1.0)
                self.assertTrue(self.sent.messages(), 'nothing sent to Stage')
                for msg in self.sent.messages()[:-1]:  # the last is the zero Twist
                    self.assertAlmostEqual(msg.linear.x, sent_v, delta=TOL)
                    self.assertAlmostEqual(msg.angular.z, sent_w, delta=TOL)
                for dx, dy, dyaw in moves[:1]:  # the first step starts from heading 0
                    self.assertAlmostEqual(math.hypot(dx, dy), sent_v * STEP_S, delta=TOL)
                    self.assertAlmostEqual(dyaw, sent_w * STEP_S, delta=TOL)
                self.assertTrue(moves)
        self.logs.wait_line('held to (0.500, 0.500) m/s: at most 0.500 m/s a wheel and 1.571 '
                            'rad/s of turn', level=Log.INFO)

    def test_non_finite_commands_are_refused(self):
        self.cmd.publish(_twist(math.nan, 0.0))
        self.cmd.publish(_twist(0.2, math.inf))
        line = self.logs.wait_line('stage_pioneer: refusing command (linear nan', level=Log.WARN)
        self.assertIn('expected finite numbers; nothing sent to the robot', line)
        # A good command after the bad ones: the first thing sent to Stage must be it, and
        # the robot drives on it (the bridge and stageros are alive and well).
        self.cmd.publish(_twist(0.1))
        first = self._first_sent('a command sent to Stage')
        self.assertEqual((first.linear.x, first.angular.z), (0.1, 0.0))
        self.truth.wait(lambda m: _pose(m)[1] > START[0] + 0.005, 'the Pioneer moving again')

    def test_stalls_at_the_wall(self):
        def stalled():
            xs = [_pose(m)[1] for m in self.truth.messages()[-6:]]
            return len(xs) == 6 and xs[0] > START[0] and len(set(xs)) == 1
        self._hold(_twist(MAX_WHEEL_MPS), stalled, 'the Pioneer stalled at the east wall',
                   WALL_DEADLINE_S)
        front = _pose(self.truth.latest())[1] + FRONT_M
        # stopped by the wall: its front in the cells before the wall's, at most a step away
        self.assertLess(front, WALL_X_M, 'the body reached into the wall')
        self.assertGreater(front, WALL_X_M - CELL_M - MAX_WHEEL_MPS * STEP_S,
                           'stopped short of the wall')
        # a second more against it: it stays where it is (commanded, not moving)
        stall_ns = stamp_ns(self.truth.latest())
        start = rospy.get_time()
        self._hold(_twist(MAX_WHEEL_MPS), lambda: rospy.get_time() - start >= 1.0,
                   'pushing the Pioneer against the wall for 1 s')
        later = [_pose(m) for m in self.truth.messages() if stamp_ns(m) >= stall_ns]
        self.assertGreaterEqual(len(later), 10)
        self.assertEqual({p[1:] for p in later}, {_pose(self.truth.latest())[1:]})
        self.assertLess(self.pose2d.latest().x + FRONT_M, WALL_X_M)

    def test_task_one_teleop_key_drives_as_on_turtlesim(self):
        # One up-arrow press of turtle_teleop_key (2.0 m/s) through pioneer_interface.py: a
        # quarter, 0.5 m/s, for the 1 s stageros keeps a command here, as turtlesim does.
        self.teleop.publish(_twist(2.0))
        sent = self._first_sent('the quarter-speed command sent to Stage')
        self.assertEqual((sent.linear.x, sent.angular.z), (0.5, 0.0))
        poses = self._wait_rest(rospy.Time.now().to_nsec() + STEP_NS)
        moves = _moves(poses)
        for dx, _, _ in moves:
            self.assertAlmostEqual(dx, 0.5 * STEP_S, delta=TOL)
        self.assertIn(len(moves), (10, 11, 12), 'steps moved for one key press (1 s)')


if __name__ == '__main__':
    rospy.init_node('test_pioneer_stage')
    rostest.rosrun('pioneer_mover', 'test_pioneer_stage', TestPioneerStage)
