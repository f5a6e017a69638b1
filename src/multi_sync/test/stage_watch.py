"""Helpers for multi_sync's Stage rostest nodes: watch the lesson's team on Stage, run Stage.

A StageWatch records what a user can see of robots 0..3 through ROS: Stage's ground truth and
odom, the robots' cmd_vel, team_status and team_positions (course_common's Recorders). Times
on Stage's topics are compared in simulated time, by their stamps: each ground-truth message
says whether the robot moved in that step (its twist is the step's finite difference) and the
odom message of the same stamp says what Stage was commanding in it, so a stall (Stage undid
a commanded move) is read exactly, whatever the load on the machine. No rospy clock is read:
a test node started with stageros may find itself on sim time or on wall time.
"""
import math
import os
import re
import unittest

from course_common.angles import yaw_from_quaternion
from course_common.processes import ROSPY_LINE
from course_common.testing import spawn, wait_for
from course_common.testing.recorders import Recorder, stamp_ns
from geometry_msgs.msg import Twist
from multi_sync.team import MONITOR_FRAME_ID
from nav_msgs.msg import Odometry
from team_watch import NodeProcess

from multi_sync.msg import RobotPosition, RobotStatus
from stage_multi import lesson_world

# The lesson's world (stage_multi): robot_N's start (x, y), all heading +x (yaw 0).
LESSON_STARTS = lesson_world.STARTS
TEAM_SIZE = len(LESSON_STARTS)
FRONT, BACK = (0, 2), (1, 3)
AHEAD_OF = {1: 0, 3: 2}  # a back robot -> the teammate in front of it, in its lane
WALL_FACE_X = -9.6  # the hall's east wall, ahead of every robot
LASER_AHEAD_M = 0.05  # the erratic's laser, ahead of its pose
# Stage's laser reads this wall 3 cm short of the geometry (its ray walk: cells looked up by
# truncation at negative coordinates, ranges to the walk's cell; stage_lite's golden data)
STAGE_READS_SHORT_M = 0.03
BODY_FRONT_M, BODY_BACK_M = 0.125, 0.225  # the erratic's footprint about its pose (origin -0.05)
POSE_TOL_M = 1e-6  # poses come from the same doubles: only float noise
MOVED_M = 0.1  # five steps at 0.2 m/s: the robot is driving, not jittering
# Ground-truth steps standing still (1 s of sim time) before a robot counts as stopped or
# stalled for good rather than between two commands.
SETTLE_STEPS = 10
STEP_NS = 100_000_000  # the world's interval_sim, 100 ms
# Stage's pace in the tests that need only the lesson's outcome (where each robot stops, what
# it logs, GO), not its pace: 4 x real time keeps the suite short. The robots' 10 Hz ticks on
# sim time still come twice per watchdog period (0.2 s of sim time), and the margins of the
# checks (0.5 m bumper, 1 m gap) leave a lagging robot 0.6 s of wall time; stage_stall and
# stage_multi, which watch Stage stall commanded robots, run at the lesson's real time.
OUTCOME_SPEEDUP = 4.0
# A rosout line in a node's rospy log file: "[rosout][INFO] <date> <time>: text".
LOG_FILE_LINE = re.compile(r'^\[rosout\]\[(\w+)\] \S+ \S+: (.*)$')


def start_stageros(stop_timeout_s=None):
    """`rosrun stage_ros stageros -g <the lesson's world>` at OUTCOME_SPEEDUP x real time,
    running (a ChildProcess: stop())."""
    return spawn(lesson_world.stageros_command('-g', '_speedup:=%s' % OUTCOME_SPEEDUP),
                 stop_timeout_s=stop_timeout_s)


def pose_of(odometry):
    """(x, y, yaw) of a nav_msgs/Odometry (m, rad)."""
    p, q = odometry.pose.pose.position, odometry.pose.pose.orientation
    return p.x, p.y, yaw_from_quaternion(q.x, q.y, q.z, q.w)


def still(truth):
    """True for a ground-truth message of a step in which the robot did not move."""
    t = truth.twist.twist
    return t.linear.x == 0.0 and t.linear.y == 0.0 and t.angular.z == 0.0


def commanded(odom):
    """True for an odom message of a step Stage ran with a non-zero command."""
    t = odom.twist.twist
    return t.linear.x != 0.0 or t.linear.y != 0.0 or t.angular.z != 0.0


def stall_runs(truths, odoms):
    """Lengths (in steps) of the runs of consecutive stalled steps: steps whose ground truth
    stood still while the odom of the same stamp shows a non-zero command. Steps missing from
    either list are left out (they break a run)."""
    commanded_at = {stamp_ns(m): commanded(m) for m in odoms}
    runs, run, last = [], 0, None
    for truth in truths:
        t = stamp_ns(truth)
        if still(truth) and commanded_at.get(t, False):
            run = run + 1 if last is not None and t - last == STEP_NS else 1
            last = t
        else:
            if run:
                runs.append(run)
            run, last = 0, None
    if run:
        runs.append(run)
    return runs


def body_gap_m(front_x, back_x):
    """Free space (m) between the back of the robot at front_x and the nose of the one behind
    it at back_x, in one lane heading +x."""
    return (front_x - BODY_BACK_M) - (back_x + BODY_FRONT_M)


def laser_to_wall_m(x):
    """What the laser of a front robot at x reads of the wall straight ahead (m): the
    distance from the laser to the wall face, as Stage's walk reads it."""
    return WALL_FACE_X - (x + LASER_AHEAD_M) - STAGE_READS_SHORT_M


def on_sim_time(lines):
    """True when a process's INFO lines (at least one) all carry a sim time: the node runs
    on Stage's /clock; False when none does (wall time)."""
    clocks = {m.group(2) is not None for m in map(ROSPY_LINE.match, lines)
              if m and m.group(1) == 'INFO'}
    if len(clocks) != 1:
        raise AssertionError('expected INFO lines on one clock, got %r' % lines)
    return clocks.pop()


def logged_texts(node):
    """What `node` (started by this test's roslaunch) logged, in order, from its log file.

    rospy writes every line a node logs to its log file too, whatever the launch file's
    output="screen" does with the screen copy, so a one-off line such as "published ready
    status" is there even if it went out before this test's /rosout subscription connected.
    The run's log folder is this test node's own (roslaunch gives every node __log there).
    """
    log_dir = os.path.dirname(os.environ['ROS_LOG_FILENAME'])
    # roslaunch names it <node>-<its process number>.log (not <node>-<n>-stdout.log, the
    # screen output of a node without output="screen").
    name = re.compile(r'^%s-\d+\.log$' % re.escape(node.lstrip('/')))
    paths = [os.path.join(log_dir, f) for f in os.listdir(log_dir) if name.match(f)]
    if len(paths) != 1:
        raise AssertionError('expected one log file of %s in %s, found %s'
                             % (node, log_dir, paths))
    with open(paths[0], encoding='utf-8') as log:
        return [m.group(2) for m in map(LOG_FILE_LINE.match, log) if m]


class StageWatch:
    """Records robots 0..n-1 of the lesson on Stage, and team_status and team_positions.

    Subscribe before the nodes start where possible; nothing here depends on it.
    """

    def __init__(self, n=TEAM_SIZE):
        self.n = n
        self.truth = [Recorder('/robot_%d/base_pose_ground_truth' % i, Odometry)
                      for i in self.ids()]
        self.odom = [Recorder('/robot_%d/odom' % i, Odometry) for i in self.ids()]
        self.cmd = [Recorder('/robot_%d/cmd_vel' % i, Twist) for i in self.ids()]
        self.status = Recorder('team_status', RobotStatus)
        self.positions = Recorder('team_positions', RobotPosition)

    def close(self):
        for recorder in (*self.truth, *self.odom, *self.cmd, self.status, self.positions):
            recorder.close()

    def ids(self):
        return range(self.n)

    # --- poses ---------------------------------------------------------------------------
    def have_poses(self):
        return all(r.latest() is not None for r in self.truth)

    def first_pose(self, i):
        return pose_of(self.truth[i].messages()[0])

    def pose(self, i):
        return pose_of(self.truth[i].latest())

    def x(self, i):
        return self.truth[i].latest().pose.pose.position.x

    def travelled_m(self, i):
        """How far robot i is from its first recorded pose (m)."""
        (x0, y0, _), (x, y, _) = self.first_pose(i), self.pose(i)
        return math.hypot(x - x0, y - y0)

    def still_since_first(self, i):
        """True while every recorded ground-truth pose of robot i is its first one."""
        poses = [pose_of(m) for m in self.truth[i].messages()]
        return all(max(abs(a - b) for a, b in zip(p, poses[0], strict=True)) <= POSE_TOL_M
                   for p in poses)

    def moved(self, ids=None, min_m=MOVED_M):
        """Robots ids (default all) are at least min_m from where they were first seen."""
        return all(self.truth[i].latest() is not None and self.travelled_m(i) >= min_m
                   for i in (self.ids() if ids is None else ids))

    def standing(self, i, steps=SETTLE_STEPS):
        """Robot i's latest `steps` ground-truth messages are steps without motion."""
        recent = self.truth[i].messages()[-steps:]
        return len(recent) == steps and all(still(m) for m in recent)

    # --- commands ------------------------------------------------------------------------
    def last_cmd(self, i):
        """linear.x of robot i's latest cmd_vel (None before the first)."""
        msg = self.cmd[i].latest()
        return None if msg is None else msg.linear.x

    def nonzero_cmds(self, i):
        return [m for m in self.cmd[i].messages()
                if m.linear.x != 0.0 or m.linear.y != 0.0 or m.angular.z != 0.0]

    def odom_speed(self, i):
        """linear.x of robot i's latest odom twist: what Stage was last commanding (m/s)."""
        msg = self.odom[i].latest()
        return None if msg is None else msg.twist.twist.linear.x

    def stall_runs(self, i):
        return stall_runs(self.truth[i].messages(), self.odom[i].messages())

    def stopped(self, i):
        """Robot i drove, then stopped itself: its command and Stage's are 0, it stands."""
        return (self.moved([i]) and self.last_cmd(i) == 0.0 and self.odom_speed(i) == 0.0
                and self.standing(i))

    def stalled(self, i):
        """Robot i stands while it commands motion and Stage still holds the command."""
        if not (self.moved([i]) and self.last_cmd(i) and self.odom_speed(i)
                and self.standing(i)):
            return False
        runs = self.stall_runs(i)
        return bool(runs) and runs[-1] >= SETTLE_STEPS

    # --- team_status ---------------------------------------------------------------------
    def gos(self):
        """The GO messages heard (team_status with header.frame_id "monitor")."""
        return [m for m in self.status.messages() if m.header.frame_id == MONITOR_FRAME_ID]

    def go_count(self):
        return len(self.gos())

    def announced(self, times):
        """Every robot's ready status heard at least `times` times."""
        counts = {}
        for m in self.status.messages():
            if m.header.frame_id != MONITOR_FRAME_ID and m.is_ready:
                counts[m.robot_id] = counts.get(m.robot_id, 0) + 1
        return all(counts.get(i, 0) >= times for i in self.ids())

    def shared_stamps(self, i):
        """The stamps (s) of robot i's positions on team_positions, in arrival order."""
        return [m.header.stamp.to_sec() for m in self.positions.messages() if m.robot_id == i]


# --- the robots' lesson lines -----------------------------------------------------------------
LINE_KINDS = (  # (letter, text with the robot's id) in the order the lesson prints them
    ('P', 'Robot %d published ready status'),
    ('W', 'Robot %d: waiting for team'),
    ('T', "Robot %d: Team is ready. Let's move!"),
)
# The workspace's line after "Let's move!": the delay from GO's arrival, in ms.
FIRST_MOVE = r'Robot %d: first move command \d+\.\d ms after GO arrived$'


def lesson_line_kinds(texts, i):
    """Robot i's lesson lines among texts, one letter each, in order: P "published ready
    status", W "waiting for team", T "Team is ready. Let's move!", F "first move command"."""
    kinds = {text % i: letter for letter, text in LINE_KINDS}
    letters = []
    for text in texts:
        if text in kinds:
            letters.append(kinds[text])
        elif re.match(FIRST_MOVE % i, text):
            letters.append('F')
    return ''.join(letters)


class LessonTestCase(unittest.TestCase):
    """The lesson's steps, for tests of multi_sync.launch: its robots wait for the team, the
    test starts `rosrun multi_sync monitor 4` as the student does, and the team drives off."""

    def robot_texts(self, i):
        return logged_texts('move_robot_%d' % i)

    def wait_team_waiting(self, watch, deadline_s):
        """Waits until Stage runs, every robot has announced itself twice and logged that it
        waits for the team; then checks that nothing moved and nobody said GO."""
        wait_for(watch.have_poses, deadline_s, "Stage's ground truth of every robot")
        wait_for(lambda: watch.announced(2), deadline_s, 'every robot to announce ready twice')
        wait_for(lambda: all('W' in lesson_line_kinds(self.robot_texts(i), i)
                             for i in watch.ids()),
                 deadline_s, "every robot's 'waiting for team' line")
        self.assertEqual(watch.gos(), [], 'GO before the monitor started')
        for i in watch.ids():
            self.assertTrue(watch.still_since_first(i), 'robot_%d moved before GO' % i)
            self.assertEqual(watch.nonzero_cmds(i), [], 'robot_%d commanded motion before GO'
                             % i)

    def start_monitor(self):
        """`rosrun multi_sync monitor 4`, stopped (and its exit code checked) at clean-up."""
        monitor = NodeProcess('monitor', str(TEAM_SIZE))
        self.addCleanup(lambda: self.assertEqual(monitor.stop(), 0, monitor.tail()))
        return monitor
