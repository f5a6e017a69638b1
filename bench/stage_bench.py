"""stageros benchmark: stage_lite's stageros, and real Stage's beside it when it is given.

    ./ws bench stage_bench [--peer STAGEROS] [--map PLAN] [--runs N]

Starts its own roscore on a free port. The worlds are the lesson's (its four erratics with
1081-beam lasers) and 20 / 50 / 100 erratics (bench/make_stage_worlds.py) on PLAN: the
workspace's office plan by default, or any floor plan of the lesson's size, such as
stage_ros's willow-full.pgm (the lesson's original map; not in this repository). For each
world, RUNS times (default 3), each simulator in turn (never two at once): stageros -g on the
world with the watchdog off (stage_lite with ~speedup -1: as fast as possible, as real Stage
runs headless), every robot sent one cmd_vel turning in place at 0.3 rad/s, and with nothing
subscribed but /clock:
* real-time factor: simulated seconds (from /clock) per wall second over WINDOW_S;
* CPU: utime + stime of the process over the same window, in cores;
* peak RSS (VmHWM) at the end of the run;
* start to every robot's first scan: from the spawn (master up) until a scan of every robot
  has arrived here (these subscribers are dropped before the window).
Medians of the runs. Then the lesson at real time: stage_lite headless and with its window
on an Xvfb display; real Stage with its window (its only real-time mode). Prints a markdown
table; with a peer, the ratio of the real-time factors (stage_lite / real Stage).

STAGEROS is real stageros's executable (stage_ros 1.8.0 on Stage 4.3.0 built from source:
src/stage/stage_lite/test/golden/README.md says how).
"""
import argparse
import contextlib
import os
import statistics
import sys
import tempfile
import threading
import time

import rosgraph
import rospy
from course_common.processes import peak_rss_mb
from course_common.testing import Xvfb, cpu_ticks, spawn, wait_for
from course_common.testing.master import Roscore
from geometry_msgs.msg import Twist, Vector3
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_stage_worlds  # bench/ is not a package: found through sys.path above

RUNS = 3
WINDOW_S = 8.0             # wall s of each flat-out measurement
REAL_TIME_WINDOW_S = 20.0  # CPU at real time: 10 ms clock ticks need a long window
TURN_RADPS = 0.3
START_DEADLINE_S = 90.0    # real Stage loads a large floor plan in a few seconds
CLK_TCK = os.sysconf('SC_CLK_TCK')
XVFB_SCREEN = (1280, 1024)  # px: room for the lesson's window
OURS = ['rosrun', 'stage_ros', 'stageros']


def cpu_s(pid):
    """CPU time (user + system) the process has used so far, s."""
    return cpu_ticks(pid) / CLK_TCK


class Bench:
    """Owns the roscore, this node's /clock subscriber and the stageros being measured."""

    def __init__(self):
        self.core = Roscore().start()  # sets ROS_MASTER_URI here, for us and our children
        rospy.init_node('stage_bench', anonymous=True, disable_signals=True)
        self._lock = threading.Lock()
        self._clock = None
        self._scans = set()
        self.clock_sub = rospy.Subscriber('/clock', Clock, self._on_clock)

    def _on_clock(self, msg):
        with self._lock:
            self._clock = (msg.clock.to_sec(), time.monotonic())

    def clock(self):
        with self._lock:
            return self._clock

    def run(self, command, world, robots, extra=(), gui=False, env=None, window_s=WINDOW_S):
        """One stageros run: (real-time factor, cores, peak RSS MB, start-to-scans s)."""
        with self._lock:
            self._clock = None
            self._scans = set()
        # a previous run's private parameters stay on the master
        with contextlib.suppress(rosgraph.MasterError):
            rosgraph.Master('/stage_bench').deleteParam('/stageros')

        def topic(i, name):  # stageros's names: relative with one robot
            return ('/robot_%d/' % i if robots > 1 else '') + name
        scan_subs = [rospy.Subscriber(topic(i, 'base_scan'), LaserScan, self._on_scan,
                                      callback_args=i)
                     for i in range(robots)]
        args = [*command, *([] if gui else ['-g']), world, *extra, '_base_watchdog_timeout:=0']
        start = time.monotonic()
        proc = spawn(args, env=env, stop_timeout_s=20.0)
        try:
            wait_for(lambda: len(self._scans) == robots, START_DEADLINE_S,
                     'a scan of every robot', alive=proc.alive)
            first_scans_s = time.monotonic() - start
            for sub in scan_subs:
                sub.unregister()
            pubs = [rospy.Publisher(topic(i, 'cmd_vel'), Twist, queue_size=1, latch=True)
                    for i in range(robots)]
            for i, pub in enumerate(pubs):
                wait_for(lambda p=pub: p.get_num_connections() > 0, START_DEADLINE_S,
                         'cmd_vel of robot %d' % i)
                pub.publish(Twist(angular=Vector3(0, 0, TURN_RADPS)))
            sim0, wall0 = wait_for(self.clock, START_DEADLINE_S, '/clock')
            cpu0 = cpu_s(proc.pid)
            time.sleep(window_s)
            sim1, wall1 = self.clock()
            cpu1 = cpu_s(proc.pid)
            wall = wall1 - wall0
            result = ((sim1 - sim0) / wall, (cpu1 - cpu0) / wall, peak_rss_mb(proc.pid),
                      first_scans_s)
            for pub in pubs:
                pub.unregister()
        finally:
            proc.stop()
        return result

    def _on_scan(self, _msg, index):
        with self._lock:
            self._scans.add(index)

    def close(self):
        self.clock_sub.unregister()
        rospy.signal_shutdown('bench done')
        self.core.stop()


def median(runs):
    return tuple(statistics.median(r[k] for r in runs) for k in range(4))


def figures(m):
    rtf, cores, rss, start = m
    return '%.2f | %.2f | %.0f | %.2f' % (rtf, cores, rss, start)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--peer', help="real stageros's executable, measured beside stage_lite's")
    ap.add_argument('--map', default=make_stage_worlds.OFFICE,
                    help='floor plan of the worlds (default: the office plan)')
    ap.add_argument('--runs', type=int, default=RUNS)
    args = ap.parse_args(argv)
    out_dir = tempfile.mkdtemp(prefix='stage_bench_')
    worlds = make_stage_worlds.write_worlds(out_dir, (4, 20, 50, 100), args.map)
    sides = [('stage_lite', OURS, ['_speedup:=-1'])]
    if args.peer:
        sides.append(('Stage', [args.peer], []))
    bench = Bench()
    rows = []
    try:
        for n, path in worlds.items():
            runs = {name: [] for name, _, _ in sides}
            for k in range(args.runs):
                for name, command, extra in sides:     # one simulator at a time, in turn
                    print('bench: %d erratics, %s, run %d of %d' % (n, name, k + 1, args.runs),
                          flush=True)
                    runs[name].append(bench.run(command, path, n, extra))
            rows.append((n, {name: median(r) for name, r in runs.items()}))
        print('bench: the lesson at real time', flush=True)
        lesson = worlds[4]
        real_time = [('stage_lite, headless', bench.run(OURS, lesson, 4, ['_speedup:=1'],
                                                        window_s=REAL_TIME_WINDOW_S))]
        with Xvfb(XVFB_SCREEN) as xvfb:
            env = {'DISPLAY': xvfb.display}
            real_time.append(('stage_lite, Tk window (Xvfb)',
                              bench.run(OURS, lesson, 4, ['_speedup:=1'], gui=True, env=env,
                                        window_s=REAL_TIME_WINDOW_S)))
            if args.peer:
                real_time.append(('Stage, its window (Xvfb)',
                                  bench.run([args.peer], lesson, 4, gui=True, env=env,
                                            window_s=REAL_TIME_WINDOW_S)))
    finally:
        bench.close()
    plan = os.path.basename(args.map)
    print()
    head = '| %s, headless, flat out | ' % plan + ' | '.join(
        '%s: real-time factor | cores | peak RSS MB | start to every first scan s' % name
        for name, _, _ in sides)
    print(head + (' | stage_lite / Stage |' if args.peer else ' |'))
    print('|---|' + '---|' * (4 * len(sides) + (1 if args.peer else 0)))
    for n, by_side in rows:
        cells = ' | '.join(figures(by_side[name]) for name, _, _ in sides)
        ratio = (' | %.2f x' % (by_side['stage_lite'][0] / by_side['Stage'][0])
                 if args.peer else '')
        print('| %s | %s%s |' % ('the lesson (4 erratics)' if n == 4 else '%d erratics' % n,
                                  cells, ratio))
    print()
    print('| the lesson at real time | real-time factor | cores | peak RSS MB | start s |')
    print('|---|---|---|---|---|')
    for name, (rtf, cores, rss, start) in real_time:
        print('| %s | %.2f | %.3f | %.0f | %.2f |' % (name, rtf, cores, rss, start))


if __name__ == '__main__':
    main()
