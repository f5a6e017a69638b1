#!/usr/bin/env python3
"""Benchmark: the master calls a 10 Hz talker makes per second, before and after the fix.

Run with `./ws bench rosout_param_bench` (no roscore needed: it runs its own master in this
process, course_common.testing.master_calls.CountingMaster, which records every XML-RPC
call). chat_pkg's talker logs every message it publishes (10 lines a second). rospy asks the
master for /rosout_disable_topics_generation on every log line while that parameter is
unset, as it is under a plain roscore; course_common.startup.init_node asks once.
  * before: the talker started as it was before the fix, with rospy.init_node;
  * after:  `rosrun chat_pkg talker` (course_common.startup.init_node).
For each, RUNS runs: the calls the talker made to the master between its WARMUP-th and its
(WARMUP + LINES)-th log line, per second of that window. Prints a markdown table of medians.
"""
import os
import signal
import statistics
import subprocess
import sys
import time
from collections import Counter

from course_common.testing.master_calls import CountingMaster

RUNS = 3
WARMUP = 5        # log lines skipped: start-up calls (registration, the one param ask)
LINES = 50        # log lines measured: 5 s at 10 Hz
LINE_DEADLINE_S = 60.0  # a talker that has not printed its lines by then is reported failed
STOP_S = 10.0

# The talker's main() before the fix, word for word but for the imports.
BEFORE = ('import rospy\n'
          'from chat_pkg.talker_node import RATE_HZ, Talker\n'
          'from course_common.startup import loop_at_rate\n'
          "rospy.init_node('talker')\n"
          'loop_at_rate(RATE_HZ, Talker().cycle)\n')
VARIANTS = [('before (rospy.init_node)', ['/usr/bin/python3', '-c', BEFORE]),
            ('after (course_common.startup.init_node)', ['rosrun', 'chat_pkg', 'talker'])]


def measure(master, argv):
    """Run one talker against master; return (calls per second by method, window in s)."""
    env = dict(os.environ, ROS_MASTER_URI=master.uri, PYTHONUNBUFFERED='1')
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True)
    try:
        start = end = None
        lines = 0
        deadline = time.monotonic() + LINE_DEADLINE_S
        for line in proc.stdout:
            if 'hello world' in line:
                lines += 1
                if lines == WARMUP:
                    start = time.monotonic()
                elif lines == WARMUP + LINES:
                    end = time.monotonic()
                    break
            if time.monotonic() > deadline:
                break
        if end is None:
            raise RuntimeError('%s printed %d lines in %.0f s' % (argv, lines, LINE_DEADLINE_S))
        calls = Counter(method for t, method, _ in master.calls(caller='/talker', since=start)
                        if t <= end)
        return {m: n / (end - start) for m, n in calls.items()}, end - start
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(STOP_S)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def main():
    master = CountingMaster()
    rows = []
    try:
        for name, argv in VARIANTS:
            totals, params, windows = [], [], []
            for _ in range(RUNS):
                per_s, window = measure(master, argv)
                totals.append(sum(per_s.values()))
                params.append(per_s.get('subscribeParam', 0.0))
                windows.append(window)
            rows.append((name, statistics.median(totals), statistics.median(params),
                         LINES / statistics.median(windows)))
    finally:
        master.stop()
    print('| talker (chat_pkg, 10 Hz) | master calls/s | of which subscribeParam/s '
          '| log lines/s |')
    print('|---|---|---|---|')
    for name, total, param, rate in rows:
        print('| %s | %.1f | %.1f | %.1f |' % (name, total, param, rate))
    print('(medians of %d runs; each window %d log lines after the first %d)'
          % (RUNS, LINES, WARMUP))
    return 0


if __name__ == '__main__':
    sys.exit(main())
