#!/usr/bin/env python3
"""Integration test of move_turtle_to_goal.py on the stand-in Pioneer: three goals in a row
(one behind, one across the heading seam), a new goal taking over, bad goals and poses, bad
gains."""
import math
import threading
import unittest

import rospy
import rostest
from course_common.angles import wrap_angle
from course_common.testing import START_DEADLINE_S, spawn, wait_for
from course_common.testing.master import publisher_has_connected
from course_common.testing.recorders import LogRecorder, Recorder
from geometry_msgs.msg import Pose2D, Twist
from turtlesim.srv import TeleportAbsolute

CONTROLLER = '/move_turtle_to_goal'
GOAL_DEADLINE_S = 90.0  # the longest goal is ~10 m at 1.2 m/s (9 s): margin for a loaded machine
POSITION_TOL_M = 0.1  # the lab's tolerances...
HEADING_TOL_RAD = 0.05
# ...plus one 16 ms tick of the last command before the stop lands: 0.314 m/s -> 5 mm,
# 0.15 rad/s -> 2.4 mrad.
TICK_SLACK_M = 0.01
TICK_SLACK_RAD = 0.005
SHORT_TURN_RAD = 2 * math.pi - 6.0  # theta 3.0 -> -3.0 the short way; the lab turns 6.0 rad
START = (5.544445, 5.544445, 0.0)  # where the stand-in Pioneer spawns: the centre, heading +x
START_TOL = 1e-4  # float32 pose fields against the teleport's float64 values


class PoseWatch:
    """The newest Pose2D, the total turn since reset, and the closest approach to a point."""

    def __init__(self):
        self._lock = threading.Lock()
        self._latest = None
        self._turned = 0.0
        self._point = None
        self._closest = math.inf
        self._sub = rospy.Subscriber('/pioneer/pose', Pose2D, self._on_pose)

    def _on_pose(self, msg):
        if not all(math.isfinite(v) for v in (msg.x, msg.y, msg.theta)):
            return  # the test's own bad pose
        with self._lock:
            if self._latest is not None:
                self._turned += abs(wrap_angle(msg.theta - self._latest.theta))
            self._latest = msg
            if self._point is not None:
                self._closest = min(self._closest, math.hypot(msg.x - self._point[0],
                                                              msg.y - self._point[1]))

    def latest(self):
        with self._lock:
            return self._latest

    def reset(self, point=None):
        with self._lock:
            self._turned, self._point, self._closest = 0.0, point, math.inf

    def turned(self):
        with self._lock:
            return self._turned

    def closest(self):
        with self._lock:
            return self._closest


def _same(msg, goal):
    """Pose2D fields are float64: the goal comes back exactly."""
    return (msg.x, msg.y, msg.theta) == tuple(float(v) for v in goal)


class TestGoToGoal(unittest.TestCase):
    """Each test starts from where the robot is, or puts it where it needs it: any order."""

    @classmethod
    def setUpClass(cls):
        cls.pose = PoseWatch()
        wait_for(cls.pose.latest, START_DEADLINE_S, 'the first /pioneer/pose')
        cls.reached = Recorder('/pioneer/goal_reached', Pose2D)
        cls.commands = Recorder('/pioneer/cmd_vel', Twist)
        cls.goal_pub = rospy.Publisher('/pioneer/goal', Pose2D, queue_size=10)
        cls.bad_pose_pub = rospy.Publisher('/pioneer/pose', Pose2D, queue_size=10)
        wait_for(lambda: publisher_has_connected(CONTROLLER, '/pioneer/cmd_vel'),
                 START_DEADLINE_S, 'the controller\'s cmd_vel connected to this test')
        wait_for(lambda: cls.goal_pub.get_num_connections() > 0
                 and cls.bad_pose_pub.get_num_connections() > 0, START_DEADLINE_S,
                 'this test\'s goal and pose publishers connected to the controller')
        cls.logs = LogRecorder(CONTROLLER)
        rospy.wait_for_service('/pioneer/teleport_absolute', START_DEADLINE_S)
        cls.teleport = rospy.ServiceProxy('/pioneer/teleport_absolute', TeleportAbsolute)

    def _start_at_centre(self):
        """Puts the idle robot back where it spawns (every goal of a test is reached or
        replaced before the test ends, so the controller sends nothing meanwhile)."""
        self.teleport(*START)
        wait_for(lambda: all(abs(a - b) < START_TOL for a, b in zip(
            (self.pose.latest().x, self.pose.latest().y, self.pose.latest().theta), START,
            strict=True)), START_DEADLINE_S, 'the robot back at its start %r' % (START,))

    def _drive_to(self, goal):
        """Sends the goal and waits until it is reported reached; returns the robot's pose."""
        start = self.reached.count()
        self.goal_pub.publish(Pose2D(*goal))
        wait_for(lambda: any(_same(m, goal) for m in self.reached.messages()[start:]),
                 GOAL_DEADLINE_S, 'goal %r reported on /pioneer/goal_reached' % (goal,))
        pose = self.pose.latest()
        self.assertLess(math.hypot(pose.x - goal[0], pose.y - goal[1]),
                        POSITION_TOL_M + TICK_SLACK_M, 'position at goal %r: %r' % (goal, pose))
        self.assertLess(abs(wrap_angle(pose.theta - goal[2])), HEADING_TOL_RAD + TICK_SLACK_RAD,
                        'heading at goal %r: %r' % (goal, pose))
        return pose

    def _reach_lines(self):
        lines = self.logs.lines()
        return lines.count('Reach position'), lines.count('Reach orientation')

    def test_three_goals_in_a_row(self):
        self._start_at_centre()
        lines_before = self._reach_lines()
        start = self.pose.latest()
        # Behind the robot, which starts at the centre heading +x.
        behind = (2.5, 5.0, 3.0)
        self.assertGreater(abs(wrap_angle(math.atan2(behind[1] - start.y, behind[0] - start.x)
                                    - start.theta)), math.pi / 2, 'the first goal is not behind')
        self._drive_to(behind)
        # Same place, heading 3.0 -> -3.0: 6.0 rad apart unwrapped, a turn of more than pi for
        # the lab's law; the short way is 0.28 rad.
        self.pose.reset()
        self._drive_to((2.5, 5.0, -3.0))
        self.assertLess(self.pose.turned(), SHORT_TURN_RAD + 0.1,
                        'the robot turned the long way round')
        self._drive_to((8.0, 8.5, 1.0))
        wait_for(lambda: self._reach_lines() == (lines_before[0] + 3, lines_before[1] + 3),
                 15.0, 'three more "Reach position" and "Reach orientation" lines')

    def test_new_goal_while_driving_takes_over(self):
        self._start_at_centre()  # 6.3 m from the first goal: the robot turns, then drives
        far = (1.0, 1.0, 0.0)
        at = self.pose.latest()
        self.pose.reset(point=far[:2])
        self.goal_pub.publish(Pose2D(*far))
        wait_for(lambda: math.hypot(self.pose.latest().x - at.x,
                                    self.pose.latest().y - at.y) > 1.0,
                 GOAL_DEADLINE_S, 'the robot 1 m on its way to %r' % (far,))
        self._drive_to((9.0, 3.0, -1.5))
        self.assertGreater(self.pose.closest(), 2.0, 'the robot kept driving to the old goal')
        self.assertFalse([m for m in self.reached.messages() if _same(m, far)],
                         'the replaced goal was reported reached')
        self.logs.wait_line('replaces (1.000, 1.000, 0.000)')

    def test_bad_goals_are_refused_and_nothing_is_sent(self):
        here = self.pose.latest()
        self.commands.clear()
        seen = len([line for line in self.logs.lines() if 'refusing goal' in line])

        def refusals():
            """This test's refusal lines, oldest first."""
            return [line for line in self.logs.lines() if 'refusing goal' in line][seen:]
        cases = (((math.nan, 5.0, 0.0), 'non-finite'), ((5.0, 5.0, math.inf), 'non-finite'),
                 ((20.0, 5.0, 0.0), 'outside the world'), ((5.0, -1.0, 0.0), 'outside the world'))
        for n, (goal, words) in enumerate(cases, start=1):
            with self.subTest(goal=goal):
                self.goal_pub.publish(Pose2D(*goal))
                wait_for(lambda n=n: len(refusals()) >= n, 15.0, 'warning %d of %d' % (n, 4))
                self.assertIn(words, refusals()[n - 1])
                self.assertIn('nothing sent', refusals()[n - 1])
        # A goal where the robot already is: reached at once, with one zero command. Anything
        # the bad goals had started would show on /pioneer/cmd_vel before it.
        self._drive_to((here.x, here.y, here.theta))
        moving = [m for m in self.commands.messages()
                  if (m.linear.x, m.angular.z) != (0.0, 0.0)]
        self.assertEqual(moving, [], 'a refused goal moved the robot')

    def test_non_finite_pose_is_ignored(self):
        self.bad_pose_pub.publish(Pose2D(math.nan, 5.0, 0.0))
        self.logs.wait_line('ignoring pose (x=nan')
        # The controller still works from the simulator's poses.
        self._drive_to((6.0, 4.0, 0.5))

    def test_bad_gains_are_fatal(self):
        for args, words in ((['_k_rho:=-1.0'], 'k_rho must be > 0'),
                            (['_k_alpha:=2.0'], 'k_alpha must be greater than k_rho'),
                            (['_rate_hz:=fast'], '~rate_hz = \'fast\'')):
            with self.subTest(args=args):
                tool = spawn(['rosrun', 'closed_loop_turtle', 'move_turtle_to_goal.py', *args])
                self.addCleanup(tool.stop)
                self.assertEqual(tool.wait_exit(START_DEADLINE_S), 1, tool.output())
                self.assertTrue(tool.lines_with(words), tool.output())


if __name__ == '__main__':
    rospy.init_node('test_go_to_goal')
    rostest.rosrun('closed_loop_turtle', 'test_go_to_goal', TestGoToGoal)
