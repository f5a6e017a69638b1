#!/usr/bin/env python3
"""Benchmark of multi_sync: how closely the robots start after GO, memory, launch time.

Run with `./ws bench multi_sync_bench` (it starts its own roscore on a free port). For teams
of 4 and 20 robots, several runs of `roslaunch multi_sync multi_sync.launch team_size:=N
monitor:=true` each, it measures:
  * GO -> first non-zero cmd_vel per robot: "sent" is the robot's own clock when it
    published the command (its log line "first move command X ms after GO"), "seen" is
    when this process received the command on robot_<i>/cmd_vel;
  * the resident memory (VmRSS) of each move_robot process;
  * the time from starting roslaunch to every robot having moved.
It prints a markdown table: medians over all robots of all runs, and maxima.
"""
import contextlib
import os
import re
import signal
import socket
import statistics
import subprocess
import sys
import threading
import time

import rosgraph
import rospy
from course_common.testing import WaitError, wait_for
from geometry_msgs.msg import Twist

from multi_sync.msg import RobotStatus

TEAMS = [(4, 5), (20, 3)]           # (team size, runs)
RUN_DEADLINE_S = 90.0               # a run that has not finished by then is reported failed
# roslaunch's output of the latest run with each team size goes here.
LAUNCH_LOG = os.path.join(os.environ.get('TMPDIR', '/tmp'), 'multi_sync_bench_%d.log')
FIRST_MOVE = re.compile(r'Robot (\d+): first move command ([0-9.]+) ms after GO')


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


class Recorder:
    """Collects the GO stamp and when each robot's first non-zero command was seen."""

    def __init__(self, max_robots):
        self.lock = threading.Lock()
        self.reset()
        rospy.Subscriber('team_status', RobotStatus, self._on_status, queue_size=1000,
                         tcp_nodelay=True)
        for i in range(max_robots):
            rospy.Subscriber('robot_%d/cmd_vel' % i, Twist, self._on_cmd, i, queue_size=10,
                             tcp_nodelay=True)

    def reset(self):
        with self.lock:
            self.go_stamp = None
            self.seen = {}

    def _on_status(self, msg):
        with self.lock:
            if msg.header.frame_id == 'monitor' and self.go_stamp is None:
                self.go_stamp = msg.header.stamp.to_sec()

    def _on_cmd(self, msg, i):
        now = time.time()
        with self.lock:
            if msg.linear.x != 0.0 and i not in self.seen:
                self.seen[i] = now

    def complete(self, n):
        with self.lock:
            return self.go_stamp is not None and len(self.seen) >= n


def robot_rss_mb(launch_pid):
    """VmRSS (MB) of each move_robot process started by the roslaunch with launch_pid."""
    sizes = []
    for pid in filter(str.isdigit, os.listdir('/proc')):
        try:
            with open('/proc/%s/stat' % pid) as f:
                ppid = int(f.read().rsplit(')', 1)[1].split()[1])
            if ppid != launch_pid:
                continue
            with open('/proc/%s/cmdline' % pid, 'rb') as f:
                if b'multi_sync/move_robot' not in f.read():
                    continue
            with open('/proc/%s/status' % pid) as f:
                for line in f:
                    if line.startswith('VmRSS:'):
                        sizes.append(int(line.split()[1]) / 1024.0)
        except (OSError, IndexError, ValueError):
            continue  # the process ended while we looked
    return sizes


def stop(launch):
    launch.send_signal(signal.SIGINT)
    try:
        launch.wait(30)
    except subprocess.TimeoutExpired:
        os.killpg(launch.pid, signal.SIGKILL)
        launch.wait()


def first_move_lines(path):
    """robot id -> ms from the robots' "first move command X ms after GO" lines in path."""
    sent = {}
    with open(path) as f:
        for match in FIRST_MOVE.finditer(f.read()):
            sent.setdefault(int(match.group(1)), float(match.group(2)))
    return sent


def one_run(recorder, n, log_path):
    """One roslaunch of n robots and the monitor; None if it did not complete in time."""
    recorder.reset()
    started = time.time()
    # The robots' screen output (nothing is lost on the way, unlike /rosout, whose
    # connections to new nodes may come up after their first lines).
    with open(log_path, 'w') as log:
        launch = subprocess.Popen(
            ['roslaunch', 'multi_sync', 'multi_sync.launch', 'team_size:=%d' % n,
             'monitor:=true'], stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        # A run that does not complete in time is reported below, not raised.
        with contextlib.suppress(WaitError):
            wait_for(lambda: recorder.complete(n), RUN_DEADLINE_S, 'every robot moving', 0.05)
        rss = robot_rss_mb(launch.pid)
        # The robots log their first-move line on their first tick after GO.
        with contextlib.suppress(WaitError):
            wait_for(lambda: len(first_move_lines(log_path)) >= n,
                     max(0.0, started + RUN_DEADLINE_S - time.time()),
                     'every first-move log line', 0.1)
    finally:
        stop(launch)
    with recorder.lock:
        go, seen = recorder.go_stamp, dict(recorder.seen)
    sent = first_move_lines(log_path)
    if go is None or len(seen) < n or len(sent) < n:
        print('bench: incomplete run: GO %s, commands seen from %s, log lines from %s (see %s)'
              % ('heard' if go else 'not heard', sorted(seen), sorted(sent), log_path),
              flush=True)
        return None
    return {'sent': list(sent.values()), 'seen': [(t - go) * 1e3 for t in seen.values()],
            'rss': rss, 'launch_s': max(seen.values()) - started}


def main():
    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    core = subprocess.Popen(['roscore', '-p', str(port)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        try:
            wait_for(rosgraph.is_master_online, 30.0, 'roscore', 0.2)
        except WaitError:
            sys.exit('bench: roscore did not start')
        rospy.init_node('multi_sync_bench', disable_signals=True)
        recorder = Recorder(max(n for n, _ in TEAMS))
        rows = []
        for n, runs in TEAMS:
            results = []
            for r in range(runs):
                result = one_run(recorder, n, LAUNCH_LOG % n)
                print('bench: %d robots, run %d: %s' % (n, r + 1, 'ok' if result else 'FAILED'),
                      flush=True)
                if result:
                    results.append(result)
            rows.append((n, runs, results))
        print()
        print('| robots | runs ok | GO→first cmd sent, median / max (ms) '
              '| GO→first cmd seen, median / max (ms) | RSS per move_robot, median / max (MB) '
              '| roslaunch→all moving, median / max (s) |')
        print('|---:|---:|---:|---:|---:|---:|')
        for n, runs, results in rows:
            if not results:
                print('| %d | 0/%d | - | - | - | - |' % (n, runs))
                continue

            def cell(key, fmt, results=results):
                values = [v for res in results for v in res[key]]
                return (fmt + ' / ' + fmt) % (statistics.median(values), max(values))

            launch_s = [res['launch_s'] for res in results]
            print('| %d | %d/%d | %s | %s | %s | %.1f / %.1f |'
                  % (n, len(results), runs, cell('sent', '%.1f'), cell('seen', '%.1f'),
                     cell('rss', '%.1f'), statistics.median(launch_s), max(launch_s)))
        print()
        print('Medians and maxima are over every robot of every run; target: max GO→first '
              'cmd under 20 ms at 20 robots.')
    finally:
        rospy.signal_shutdown('bench done')
        core.send_signal(signal.SIGINT)
        try:
            core.wait(20)
        except subprocess.TimeoutExpired:
            os.killpg(core.pid, signal.SIGKILL)


if __name__ == '__main__':
    main()
