#!/usr/bin/env python3
"""The swarm through ROS across hosts: what splitting the controller over machines buys.

    ./ws bench swarm_hosts_bench [--robots 1000] [--runs 3] [--window 10]

Root and `ip netns` (src/multihost: hosts are network namespaces on this machine); without,
it says why and exits 0. For N swarmbots (stage_lite.swarm_world's ROS swarm: swarm.launch
with controller:=false, flat out), each layout RUNS times, the layouts in turn:
* one host, one node: stageros and one swarm_controller driving all N, on host 1 (as
  swarm_ros_bench, but through roslaunch and the hosts' addresses);
* one host, two nodes: the same, the robots split between two swarm_controller processes
  (robots 0..N/2-1 and N/2..N-1) on host 1;
* three hosts: stageros on host 1, the two nodes on hosts 2 and 3 (ROS 1's networking over
  the namespaces' bridge, as across a lab's switch).
Figures, medians of the runs: start-up (from the controllers' start to the last one's line
that every robot's first scan arrived), the real-time factor from /clock over WINDOW wall s
after WARMUP_S, and the cores of stageros and of the controllers together (/proc, over the
same window). Every host here shares this machine's cores: a real second machine would
bring cores of its own, so what is measured is the split into processes (a GIL each) and the
network path, not more CPU.
"""
import argparse
import contextlib
import os
import statistics
import sys
import tempfile
import threading
import time

from course_common.processes import descendants
from course_common.waiting import wait_for
from multihost.harness import Team
from multihost.hosts import Hosts, unavailable_reason
from multihost.lessons import start_swarm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stage_bench  # bench/ is not a package: found through sys.path above

RUNS = 3
ROBOTS = 1000
WARMUP_S = 3.0
WINDOW_S = 10.0
START_DEADLINE_S = 300.0
FIRST_SCANS_LINE = "every robot's first scan received"
LAYOUTS = {
    'one host, one node': {'sim': 1, 'swarm_a': 1, 'swarm_b': None},
    'one host, two nodes': {'sim': 1, 'swarm_a': 1, 'swarm_b': 1},
    'three hosts': {'sim': 1, 'swarm_a': 2, 'swarm_b': 3},
}
# /clock on host 1, a line "<sim s> <wall s>" whenever it moves (at most 10 a wall second)
CLOCK_WATCHER = """
import time, rospy
from rosgraph_msgs.msg import Clock
rospy.init_node('swarm_hosts_clock', disable_signals=True)
last = [0.0]
def heard(msg):
    now = time.time()
    if now - last[0] >= 0.1:
        last[0] = now
        print('clock %.6f %.6f' % (msg.clock.to_sec(), now), flush=True)
rospy.Subscriber('/clock', Clock, heard, queue_size=1)
rospy.spin()
"""


class Clock:
    """The newest (sim s, wall s) the clock watcher printed."""

    def __init__(self):
        self._lock = threading.Lock()
        self.latest = None

    def on_line(self, line):
        parts = line.split()
        if len(parts) == 3 and parts[0] == 'clock':
            with self._lock:
                self.latest = (float(parts[1]), float(parts[2]))

    def read(self):
        with self._lock:
            return self.latest


def tree_cpu_s(proc):
    """CPU s of a team process and everything under it (roslaunch/rosrun and the node)."""
    total = 0.0
    for pid in descendants(proc.proc.pid):
        with contextlib.suppress(OSError):  # ended meanwhile
            total += stage_bench.cpu_s(pid)
    return total


def run(hosts, layout, robots, window_s, log_dir):
    """One run of a layout: dict of the figures."""
    team = Team(hosts, log_dir)
    clock = Clock()
    try:
        start_swarm(team, robots, layout, speedup=-1, probe=False)
        nodes = [n for n in ('swarm_a', 'swarm_b') if layout[n] is not None]
        team.start('clock', 1, [sys.executable, '-c', CLOCK_WATCHER], on_line=clock.on_line)
        wait_for(lambda: all(team.procs[n].printed(FIRST_SCANS_LINE) for n in nodes),
                 START_DEADLINE_S, 'every first scan at the controllers',
                 alive=lambda: not team.exited())
        start_s = time.time() - team.started_at['swarm_a']     # the controllers' start
        time.sleep(WARMUP_S)        # the measurement's warm-up, not a wait for a condition
        sim0, wall0 = wait_for(clock.read, START_DEADLINE_S, '/clock')
        cpu0 = [tree_cpu_s(team.procs[n]) for n in ['sim', *nodes]]
        time.sleep(window_s)        # the measurement window itself
        sim1, wall1 = clock.read()
        cpu1 = [tree_cpu_s(team.procs[n]) for n in ['sim', *nodes]]
        wall = wall1 - wall0
        return dict(rtf=(sim1 - sim0) / wall, sim_cores=(cpu1[0] - cpu0[0]) / wall,
                    node_cores=sum(cpu1[1:]) / wall - sum(cpu0[1:]) / wall, start=start_s)
    finally:
        team.close()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--robots', type=int, default=ROBOTS)
    ap.add_argument('--runs', type=int, default=RUNS)
    ap.add_argument('--window', type=float, default=WINDOW_S, help='wall s measured')
    args = ap.parse_args(argv)
    reason = unavailable_reason()
    if reason:
        print('swarm_hosts_bench: skipped: %s' % reason)
        return 0
    results = {name: [] for name in LAYOUTS}
    with tempfile.TemporaryDirectory(prefix='swarm_hosts_') as logs, \
            Hosts('wsb%d' % os.getpid(), 3) as hosts:
        for k in range(args.runs):
            for name, layout in LAYOUTS.items():
                print('bench: %d swarmbots, %s, run %d of %d' % (args.robots, name, k + 1,
                                                                args.runs), flush=True)
                r = run(hosts, layout, args.robots, args.window,
                        os.path.join(logs, '%s_%d' % (name.replace(' ', '_'), k)))
                print('bench:   ' + ', '.join('%s %.3g' % kv for kv in r.items()), flush=True)
                results[name].append(r)
    print()
    print('| %d swarmbots | real-time factor | stageros cores | controllers cores | start to '
          'every first scan s |' % args.robots)
    print('|---|---|---|---|---|')
    for name, runs in results.items():
        med = {key: statistics.median(r[key] for r in runs) for key in runs[0]}
        print('| %s | %.2f | %.2f | %.2f | %.1f |' % (name, med['rtf'], med['sim_cores'],
                                                     med['node_cores'], med['start']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
