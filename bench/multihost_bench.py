#!/usr/bin/env python3
"""Benchmark of the lessons across hosts: one host against three, with netem when available.

Run with `./ws bench multihost_bench` as root (network namespaces, see src/multihost). For
each layout (every role on host 1; the lesson's three hosts; three hosts with
`tc netem delay 20ms loss 1%` on the switch, if the kernel has sch_netem) it measures:
  * multi_sync, RUNS runs: GO -> each robot's first command, as the robot logs it
    ("first move command X ms after GO": GO's transit to its host plus its reaction), and as
    seen on host 1 (the command's trip back included);
  * convoy, CONVOY_S seconds with the autopilot: follower pose -> its command, seen on host 1
    (pose out to the follower's host, convoy_node, command back), per follower, each
    command paired with the follower pose nearest in time (valid below 8 ms).
Prints a markdown table. Without root or `ip netns` it says why and exits 0.
"""
import os
import re
import statistics
import sys
import tempfile
import time

from course_common.testing import wait_for
from multihost.harness import Team
from multihost.hosts import Hosts, HostsError, unavailable_reason
from multihost.lessons import (
    CONVOY_HOSTS,
    MULTI_SYNC_HOSTS,
    MULTI_SYNC_ROBOTS,
    one_host,
    start_convoy,
    start_multi_sync,
)

RUNS = 3
CONVOY_S = 20.0   # of pose/command pairs after the followers start, ~1250 per follower
NETEM = ['delay', '20ms', 'loss', '1%']
FIRST_MOVE = re.compile(r'Robot (\d+): first move command ([0-9.]+) ms after GO')


def multi_sync_run(hosts, layout, log_dir):
    """(robot-logged ms, seen-on-host-1 ms) lists for one run."""
    team = Team(hosts, log_dir)
    try:
        probe = start_multi_sync(team, layout)
        go = wait_for(probe.go_stamp, 60.0, 'GO')
        seen = [wait_for(lambda r=r: probe.first_move(r), 30.0, 'a command of ' + r) - go
                for r in MULTI_SYNC_ROBOTS]
        logged = {}

        def all_logged():
            for name in ('robots_01', 'robots_23'):
                with open(team.log_path(name), encoding='utf-8', errors='replace') as f:
                    logged.update((int(i), float(ms)) for i, ms in FIRST_MOVE.findall(f.read()))
            return len(logged) == len(MULTI_SYNC_ROBOTS)
        wait_for(all_logged, 30.0, "the robots' first-move log lines")
        return list(logged.values()), [1000.0 * s for s in seen]
    finally:
        team.close()


def convoy_run(hosts, layout, log_dir):
    """{follower: [pose -> command ms]} seen on host 1."""
    team = Team(hosts, log_dir)
    try:
        probe = start_convoy(team, layout, pose_period_s=0.0)
        wait_for(lambda: probe.events('cmd', 'robot3'), 60.0, "robot3's first command")
        start = time.time()
        time.sleep(CONVOY_S)  # the measurement window itself, not a wait for a condition
        result = {}
        for follower in ('robot2', 'robot3'):
            poses = [e['t'] for e in probe.events('pose', follower, since=start)]
            latencies, k = [], 0
            for cmd in probe.events('cmd', follower, since=start):
                while k + 1 < len(poses) and poses[k + 1] <= cmd['t']:
                    k += 1
                # The pose nearest in time caused the command (valid while the latency is
                # below half the 16 ms pose period). The probe hears the pose in another
                # thread than the command, so it can hear the command first: that counts 0.
                near = min(poses[k:k + 2], key=lambda t, c=cmd['t']: abs(c - t), default=None)
                if near is not None:
                    latencies.append(max(0.0, 1000.0 * (cmd['t'] - near)))
            result[follower] = latencies
        return result
    finally:
        team.close()


def stats(values, p95=False):
    """'median / max', or 'median / p95 / max' (ms)."""
    if not values:
        return '-'
    ordered = sorted(values)
    cells = [statistics.median(ordered)]
    if p95:
        cells.append(ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))])
    return ' / '.join('%.1f' % v for v in [*cells, ordered[-1]])


def main():
    reason = unavailable_reason()
    if reason:
        print('multihost_bench: not run: %s' % reason)
        return 0
    log_root = tempfile.mkdtemp(prefix='multihost_bench_')
    rows = []
    with Hosts('wsh%d' % os.getpid(), 3) as hosts:
        layouts = [('one host', one_host(MULTI_SYNC_HOSTS), one_host(CONVOY_HOSTS), None),
                   ('three hosts', MULTI_SYNC_HOSTS, CONVOY_HOSTS, None),
                   ('three hosts, netem %s' % ' '.join(NETEM), MULTI_SYNC_HOSTS, CONVOY_HOSTS,
                    NETEM)]
        for label, ms_layout, cv_layout, netem in layouts:
            if netem:
                try:
                    hosts.netem(netem)
                except HostsError as err:
                    print('multihost_bench: %s: not available on this kernel (%s)'
                          % (label, str(err).split(': ', 1)[-1]))
                    continue
            logged, seen = [], []
            for run in range(RUNS):
                a, b = multi_sync_run(hosts, ms_layout, os.path.join(log_root, '%s-ms%d' % (
                    label.split(',')[0].replace(' ', '_'), run)))
                logged += a
                seen += b
                print('multihost_bench: %s, multi_sync run %d done' % (label, run + 1),
                      flush=True)
            convoy = convoy_run(hosts, cv_layout, os.path.join(log_root, '%s-convoy' % (
                label.split(',')[0].replace(' ', '_'))))
            print('multihost_bench: %s, convoy done' % label, flush=True)
            rows.append((label, stats(logged), stats(seen), stats(convoy['robot2'], True),
                         stats(convoy['robot3'], True), len(convoy['robot2'])))
            if netem:
                hosts.netem([])
    print()
    print('| layout | GO → first command, robot log, median / max (ms) | GO → command seen on '
          'host 1, median / max (ms) | robot2 pose → command, median / p95 / max (ms) | '
          'robot3 pose → command, median / p95 / max (ms) |')
    print('|---|---:|---:|---:|---:|')
    for label, logged, seen, r2, r3, _n in rows:
        print('| %s | %s | %s | %s | %s |' % (label, logged, seen, r2, r3))
    print()
    print('multi_sync: %d runs x 4 robots per layout; convoy: %.0f s, %s pose/command pairs '
          'per follower. Logs: %s' % (RUNS, CONVOY_S, rows[0][5] if rows else 0, log_root))
    return 0


if __name__ == '__main__':
    sys.exit(main())
