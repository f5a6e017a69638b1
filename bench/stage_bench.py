"""stageros benchmark: the issue's figures for real Stage 4.3 + stage_ros 1.8.0, run on stage_lite.

Run with `./ws bench stage_bench` (devel space sourced, /usr/bin/python3). It starts its own
roscore on a free port and, for each world (the lesson's, and 20 / 50 / 100 erratics from
bench/make_stage_worlds.py), starts `rosrun stage_ros stageros -g WORLD` with ~speedup -1 and
the watchdog off, sends every robot one cmd_vel turning in place at 0.3 rad/s, and measures,
with nothing subscribed but /clock:
* real-time factor: simulated seconds (from /clock) per wall second over WINDOW_S;
* CPU: utime + stime of the process over the same window, in cores;
* peak RSS (VmHWM) at the end of the run;
* start to every robot's first scan: from the spawn (master up) until a scan of every robot has
  arrived here (these subscribers are dropped before the window).
Median of RUNS runs. Then, on the lesson world at real time (~speedup 1): CPU headless
(-g) and with the Tk window on an Xvfb display (no -g). Prints a markdown table beside real
Stage's figures (../shared/STAGE.md section 6, issue 18).
"""
import os
import statistics
import sys
import tempfile
import threading
import time

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
WINDOW_S = 8.0            # wall s of each flat-out measurement
REAL_TIME_WINDOW_S = 20.0  # CPU at real time: 10 ms clock ticks need a long window
TURN_RADPS = 0.3
START_DEADLINE_S = 60.0
CLK_TCK = os.sysconf('SC_CLK_TCK')
LESSON = make_stage_worlds.LESSON
#: Real Stage 4.3.0 + stage_ros 1.8.0 (issue 18): (real-time factor, cores, peak RSS MB).
REFERENCE = {'lesson': (26.1, 1.0, 647), 20: (3.63, 1.0, 661), 50: (1.39, 1.0, 687),
             100: (0.61, 1.0, 732)}
REFERENCE_START_S = 2.1
REFERENCE_WINDOW = (0.23, 760)
XVFB_SCREEN = (1280, 1024)  # px: room for the lesson's window


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

    def run(self, world, robots, speedup=-1.0, gui=False, env=None, window_s=WINDOW_S):
        """One stageros run: (real-time factor, cores, peak RSS MB, start-to-scans s)."""
        with self._lock:
            self._clock = None
            self._scans = set()
        def topic(i, name):  # stageros's names: relative with one robot
            return ('/robot_%d/' % i if robots > 1 else '') + name
        scan_subs = [rospy.Subscriber(topic(i, 'base_scan'), LaserScan, self._on_scan,
                                      callback_args=i)
                     for i in range(robots)]
        args = ['rosrun', 'stage_ros', 'stageros', *([] if gui else ['-g']), world,
                '_speedup:=%g' % speedup, '_base_watchdog_timeout:=0']
        start = time.monotonic()
        proc = spawn(args, env=env, stop_timeout_s=20.0)
        try:
            wait_for(lambda: len(self._scans) == robots, START_DEADLINE_S,
                     'a scan of every robot', alive=proc.alive)
            first_scans_s = time.monotonic() - start
            for sub in scan_subs:
                sub.unregister()
            pubs = [rospy.Publisher(topic(i, 'cmd_vel'), Twist, queue_size=1)
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


def _median_runs(bench, world, robots):
    runs = [bench.run(world, robots) for _ in range(RUNS)]
    return tuple(statistics.median(r[k] for r in runs) for k in range(4))


def main():
    out_dir = tempfile.mkdtemp(prefix='stage_bench_')
    worlds = [('lesson', LESSON, 4)] + [(n, path, n) for n, path in
                                       make_stage_worlds.write_worlds(out_dir).items()]
    bench = Bench()
    rows = []
    try:
        for key, path, robots in worlds:
            print('bench: %s, %d runs' % (key, RUNS), flush=True)
            rows.append((key, robots, _median_runs(bench, path, robots)))
        print('bench: lesson at real time, headless and with the window', flush=True)
        headless = bench.run(LESSON, 4, speedup=1.0, window_s=REAL_TIME_WINDOW_S)
        with Xvfb(XVFB_SCREEN) as xvfb:
            window = bench.run(LESSON, 4, speedup=1.0, gui=True,
                               env={'DISPLAY': xvfb.display}, window_s=REAL_TIME_WINDOW_S)
    finally:
        bench.close()
    print()
    print('| world (headless, ~speedup -1) | real-time factor (Stage) | CPU, cores (Stage) '
          '| peak RSS MB (Stage) | start to every first scan s (Stage) |')
    print('|---|---|---|---|---|')
    for key, robots, (rtf, cores, rss, start) in rows:
        ref = REFERENCE[key]
        name = 'the lesson (4 erratics)' if key == 'lesson' else '%d erratics' % robots
        print('| %s | %.2f (%.2f) | %.2f (%.1f) | %.0f (%d) | %.2f (%s) |'
              % (name, rtf, ref[0], cores, ref[1], rss, ref[2], start,
                 REFERENCE_START_S if key == 'lesson' else '-'))
    print('| the lesson at real time, headless | %.2f | %.3f | %.0f | %.2f |'
          % (headless[0], headless[1], headless[2], headless[3]))
    print('| the lesson at real time, Tk window (Xvfb) | %.2f | %.3f (%.2f) | %.0f (%d) | '
          '%.2f (2.4) |' % (window[0], window[1], REFERENCE_WINDOW[0], window[2],
                            REFERENCE_WINDOW[1], window[3]))


if __name__ == '__main__':
    main()
