#!/usr/bin/env python3
"""Integration test: convoy_demo records its run to a bag, and bag_report, run on that bag,
prints the demo's gap figures, which agree with the gaps this test computes itself from the
pose topics while the demo runs; bag_report reads a bag named like the course's C++ convoy and
rejects what is not a convoy bag with one line and a non-zero exit.

Runs the real executables with rosrun (the demo starts its own master on a free port, which
this test joins to listen to the poses); the bags of the bag_report cases are written here
with the rosbag API.
"""
import math
import os
import re
import subprocess
import threading
import time
from bisect import bisect_right

import rosbag
import rospy
import rostest
from convoy.bag_report import summarise_bag
from course_common.testing import ScratchDirTestCase, spawn, wait_for
from geometry_msgs.msg import Twist
from std_msgs.msg import String
from turtlesim.msg import Pose

PKG = 'convoy'
DEMO_DURATION_S = 6  # enough for both followers to move; the figures need not be good ones
DEMO_TIMEOUT_S = 150.0  # start-up, 6 s recorded, shutdown, on a loaded 2-core machine
REPORT_TIMEOUT_S = 60.0
SAME_FIGURE_M = 0.01  # the "same gap figures (within 1 cm)"
MASTER_LINE_TIMEOUT_S = 60.0  # the demo's first line (its master is up), on a loaded machine
# Live gaps against the bag's: both pair each follower pose with the newest leader pose their
# subscriber had received, and two subscribers can see the poses of one tick in a different
# order, so a pair may take leader poses one tick apart: a leader moves at most
# 0.3 /s x 8 m = 2.4 m/s (a follower catching up from the corner) x 16 ms = 0.04 m.
LIVE_VS_BAG_M = 0.04
# The demo records 6 s once rosbag hears every robot; this test's own subscriber connects in
# the same seconds, so it hears most of that window (and the figures are compared on the part
# both heard).
MIN_SHARED_S = DEMO_DURATION_S / 2
MASTER_LINE = re.compile(r'^convoy_demo: \d+ robots, master (\S+), recording')
PNG_MAGIC = b'\x89PNG\r\n\x1a\n'
POSE_PERIOD_S = 0.016  # turtlesim publishes every pose each 16 ms


def run(args, timeout_s):
    return subprocess.run(args, capture_output=True, text=True, timeout=timeout_s, check=False)


def bag_report(*args):
    return run(['rosrun', 'convoy', 'bag_report'] + list(args), REPORT_TIMEOUT_S)


def master_uri(lines):
    """The master convoy_demo names in its first line (None until it printed it)."""
    for line in lines:
        match = MASTER_LINE.match(line)
        if match:
            return match.group(1)
    return None


class LivePoses:
    """Every pose of robot1..robot<n> this node receives, as (t_s, x_m, y_m), t the wall clock
    at arrival: the clock rosbag stamps each message of a bag with (no sim time here)."""

    def __init__(self, n_robots):
        self._lock = threading.Lock()
        self._tracks = {'robot%d' % i: [] for i in range(1, n_robots + 1)}
        self._subs = [rospy.Subscriber('/%s/pose' % robot, Pose, self._on_pose, robot,
                                       queue_size=10000)
                      for robot in self._tracks]

    def _on_pose(self, msg, robot):
        now = time.time()
        with self._lock:
            self._tracks[robot].append((now, msg.x, msg.y))

    def tracks(self):
        with self._lock:
            return {robot: list(samples) for robot, samples in self._tracks.items()}


def live_gaps(leader, follower, start_s, end_s):
    """Gaps (m) of the follower samples in [start_s, end_s], each to the newest leader sample
    at or before it: this test's own pairing of what it heard, not convoy.metrics'."""
    leader_times = [t for t, _, _ in leader]
    gaps = []
    for t, x, y in follower:
        k = bisect_right(leader_times, t) - 1
        if start_s <= t <= end_s and k >= 0:
            gaps.append(math.hypot(leader[k][1] - x, leader[k][2] - y))
    return gaps


def table_rows(text):
    """{'robot2 -> robot1': (mean_m, max_m)} from the gap table in a command's output."""
    rows = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if len(cells) == 5 and ' -> ' in cells[0]:
            rows[cells[0]] = (float(cells[1]), float(cells[2]))
    return rows


def is_png(path):
    with open(path, 'rb') as png:
        return png.read(len(PNG_MAGIC)) == PNG_MAGIC


def write_course_bag(path, seconds=4.0):
    """A bag as `rosbag record` of the course's C++ convoy on turtlesim would hold it:
    /robot1..3/pose (turtlesim/Pose) and /robot2..3/cmd_vel. robot1 drives along y = 5 at
    0.5 m/s; robot2 keeps 2 m behind it and robot3 1.5 m behind robot2 (from t = 0.5 s)."""
    with rosbag.Bag(path, 'w') as bag:
        for k in range(round(seconds / POSE_PERIOD_S)):
            t = 100.0 + k * POSE_PERIOD_S
            x1 = 3.0 + 0.5 * k * POSE_PERIOD_S
            stamp = rospy.Time.from_sec(t)
            bag.write('/robot1/pose', Pose(x=x1, y=5.0, linear_velocity=0.5), stamp)
            bag.write('/robot2/pose', Pose(x=x1 - 2.0, y=5.0), stamp + rospy.Duration(0.001))
            bag.write('/robot2/cmd_vel', Twist(), stamp + rospy.Duration(0.002))
            if t >= 100.5:
                bag.write('/robot3/pose', Pose(x=x1 - 3.5, y=5.0), stamp + rospy.Duration(0.003))
                bag.write('/robot3/cmd_vel', Twist(), stamp + rospy.Duration(0.004))


class TestConvoyBag(ScratchDirTestCase):
    TMP_PREFIX = 'test_convoy_bag_'

    def assert_rejected(self, result, reason):
        self.assertEqual(result.returncode, 1, result.stderr)
        lines = result.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, 'expected one line, got:\n%s' % result.stderr)
        self.assertTrue(lines[0].startswith('bag_report: error: '), lines[0])
        self.assertIn(reason, lines[0])
        self.assertEqual(result.stdout, '')

    def run_demo_listening(self, out):
        """Runs convoy_demo; joins its master as soon as the demo names it and records every
        pose until the demo exits. Returns (exit code, its output, live tracks)."""
        demo = spawn(['rosrun', 'convoy', 'convoy_demo', '--out', out,
                      '--duration', str(DEMO_DURATION_S)], env={'PYTHONUNBUFFERED': '1'})
        self.addCleanup(demo.stop)
        try:
            uri = wait_for(lambda: master_uri(demo.lines()), MASTER_LINE_TIMEOUT_S,
                           "convoy_demo's line naming its master", alive=demo.alive)
            # This process's one node, on the demo's master (rostest's master is not needed:
            # the results go to a file).
            os.environ['ROS_MASTER_URI'] = uri
            rospy.init_node('test_convoy_bag_live', anonymous=True, disable_signals=True)
            live = LivePoses(3)
        finally:
            code = demo.wait_exit(DEMO_TIMEOUT_S)
        return code, demo.output(), live.tracks()

    def test_demo_bag_gives_the_demo_figures(self):
        out = self.path('demo')
        code, output, live = self.run_demo_listening(out)
        self.assertEqual(code, 0, output)
        bag_path = os.path.join(out, 'convoy.bag')
        self.assertIn('bag:    %s' % bag_path, output)
        with rosbag.Bag(bag_path) as bag:
            topics = bag.get_type_and_topic_info().topics
        for i in (1, 2, 3):
            self.assertEqual(topics['/robot%d/pose' % i].msg_type, 'turtlesim/Pose')
            self.assertEqual(topics['/robot%d/cmd_vel' % i].msg_type, 'geometry_msgs/Twist')
            self.assertGreater(topics['/robot%d/pose' % i].message_count, 0)
            self.assertGreater(topics['/robot%d/cmd_vel' % i].message_count, 0)
        for png in ('convoy_trails.png', 'convoy_gaps.png', 'convoy_canvas.png'):
            self.assertTrue(is_png(os.path.join(out, png)), png)

        report = bag_report(bag_path, '--out', self.path('remade'))
        self.assertEqual(report.returncode, 0, report.stderr)
        demo_rows, report_rows = table_rows(output), table_rows(report.stdout)
        self.assertEqual(set(demo_rows), {'robot2 -> robot1', 'robot3 -> robot2'})
        self.assertEqual(set(report_rows), set(demo_rows))
        # The demo prints its table with bag_report's code: this checks that the command
        # remakes it from the bag alone, not that the figures are right (that is below).
        for row, (mean_m, max_m) in demo_rows.items():
            self.assertAlmostEqual(report_rows[row][0], mean_m, delta=SAME_FIGURE_M, msg=row)
            self.assertAlmostEqual(report_rows[row][1], max_m, delta=SAME_FIGURE_M, msg=row)
        for png in ('convoy_trails.png', 'convoy_gaps.png'):
            self.assertTrue(is_png(os.path.join(self.path('remade'), png)), png)

        # An independent computation: the gaps this test heard live on the pose topics,
        # against bag_report's gaps from the bag, over the part of the run both heard.
        bag = summarise_bag(bag_path)
        self.assertTrue(all(live.values()), 'no live pose of %s'
                        % [robot for robot, samples in live.items() if not samples])
        start = max(bag.start_s, max(samples[0][0] for samples in live.values()))
        end = min(bag.start_s + bag.duration_s, min(samples[-1][0] for samples in live.values()))
        self.assertGreaterEqual(end - start, MIN_SHARED_S,
                                'this test heard %.1f s of the %.1f s in the bag'
                                % (end - start, bag.duration_s))
        for pair in bag.pairs:
            row = '%s -> %s' % (pair.follower, pair.leader)
            from_bag = [g for t, g in pair.gaps if start <= bag.start_s + t <= end]
            heard = live_gaps(live[pair.leader], live[pair.follower], start, end)
            self.assertTrue(from_bag and heard, row)
            self.assertAlmostEqual(sum(heard) / len(heard), sum(from_bag) / len(from_bag),
                                   delta=LIVE_VS_BAG_M, msg='mean gap, ' + row)
            self.assertAlmostEqual(max(heard), max(from_bag), delta=LIVE_VS_BAG_M,
                                   msg='max gap, ' + row)

    def test_bag_of_the_course_convoy(self):
        bag_path = self.path('course.bag')
        write_course_bag(bag_path)
        result = bag_report(bag_path, '--out', self.path('course'))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn('3 robots (robot1, robot2, robot3)', result.stdout)
        rows = table_rows(result.stdout)
        self.assertEqual(list(rows), ['robot2 -> robot1', 'robot3 -> robot2'])
        # robot2's pose comes 1 ms after robot1's: the leader's newest pose is of that tick.
        self.assertEqual(rows['robot2 -> robot1'], (2.0, 2.0))
        self.assertEqual(rows['robot3 -> robot2'], (1.5, 1.5))
        for png in ('course_trails.png', 'course_gaps.png'):
            self.assertTrue(is_png(os.path.join(self.path('course'), png)), png)

    def test_pairs_option(self):
        bag_path = self.path('pairs.bag')
        write_course_bag(bag_path)
        result = bag_report(bag_path, '--out', self.path('pairs'), '--pairs', 'robot3:robot1')
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(table_rows(result.stdout), {'robot3 -> robot1': (3.5, 3.5)})
        self.assert_rejected(bag_report(bag_path, '--pairs', 'robot4:robot1'),
                             'no pose topic for robot4')

    def test_rejects_a_file_that_is_not_a_bag(self):
        path = self.path('notes.bag')
        with open(path, 'w') as text:
            text.write('robot1 robot2 robot3\n')
        self.assert_rejected(bag_report(path), 'not a readable bag file')

    def test_rejects_an_unindexed_bag(self):
        # What a recorder killed before it closed its bag leaves: data without the index.
        whole, cut = self.path('whole.bag'), self.path('cut.bag')
        write_course_bag(whole)
        with open(whole, 'rb') as src, open(cut, 'wb') as dst:
            dst.write(src.read(os.path.getsize(whole) // 2))
        self.assert_rejected(bag_report(cut), 'run "rosbag reindex %s" first' % cut)

    def test_rejects_a_missing_file(self):
        self.assert_rejected(bag_report(self.path('missing.bag')), 'No such file')

    def test_rejects_a_bag_without_pose_topics(self):
        path = self.path('no_poses.bag')
        with rosbag.Bag(path, 'w') as bag:
            for k in range(10):
                stamp = rospy.Time.from_sec(10.0 + k)
                bag.write('/robot1/cmd_vel', Twist(), stamp)
                bag.write('/robot2/pose', String(data='not a turtlesim pose'), stamp)
        self.assert_rejected(bag_report(path), 'no <robot>/pose topic of type turtlesim/Pose')

    def test_rejects_a_bag_of_one_robot(self):
        path = self.path('one.bag')
        with rosbag.Bag(path, 'w') as bag:
            bag.write('/turtle1/pose', Pose(x=1.0), rospy.Time.from_sec(1.0))
        self.assert_rejected(bag_report(path), 'at least two robots')

    def test_rejects_bad_arguments(self):
        for args in ([], ['x.bag', '--within', '-1'], ['x.bag', '--within', 'nan']):
            result = bag_report(*args)
            self.assertEqual(result.returncode, 2, args)
            self.assertIn('bag_report: error:', result.stderr)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'convoy_bag', TestConvoyBag)
