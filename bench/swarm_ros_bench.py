"""The swarm through ROS: stageros on N swarmbots and one swarm_controller node driving them
all, stage_lite's stageros against real stageros with the same node.

    ./ws bench swarm_ros_bench [--peer STAGEROS] [--robots 100 1000] [--runs 3] [--window 10]
                               [--without-node]

Starts its own roscore on a free port. The worlds are stage_lite.swarm_world's ROS swarms
(world_text(N, ros=True): Stage's benchmark swarmbot, its 12 infrared readings as one
12-sample sensor, on the hospital's open floor). For each N, RUNS times, each simulator in
turn (never two at once): /use_sim_time set, then stageros -g (flat out: the world says
`speedup -1`, as real Stage runs headless) and `swarm_controller _robots:=N` (10 Hz of sim
time) spawned together, as a launch file starts them:
* start-up: from the spawn to the node's line that every robot's first scan has arrived;
* real-time factor: simulated seconds (from /clock) per wall second over WINDOW_S wall s,
  after WARMUP_S;
* CPU of stageros and of the node: utime + stime over the same window, in cores (/proc);
* peak RSS (VmHWM) of each at the end; the robots' spread (odom) the node reports last.
--without-node: stageros alone, nothing subscribed but /clock (start-up: to the first /clock).
Medians of the runs; a markdown table. STAGEROS: real stageros's executable (stage_ros 1.8.0
on Stage 4.3.0, built as /work/shared/STAGE.md section 7 says), which needs libstage on
LD_LIBRARY_PATH (--peer-lib, default: the executable's ../../../../install/lib if there).
"""
import argparse
import contextlib
import os
import statistics
import sys
import tempfile
import time

import rosgraph
from course_common.processes import peak_rss_mb
from course_common.testing import spawn, wait_for
from stage_lite import swarm_world

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stage_bench  # bench/ is not a package: found through sys.path above

RUNS = 3
COUNTS = (100, 1000)
WARMUP_S = 3.0            # wall s after every first scan before the window
WINDOW_S = 10.0           # wall s of each measurement
START_DEADLINE_S = 240.0
OURS = ['rosrun', 'stage_ros', 'stageros']
NODE = ['rosrun', 'swarm', 'swarm_controller']
FIRST_SCANS_LINE = "every robot's first scan received"
#: runs of one simulator in a row before the bench gives up (the real stageros dies now and
#: then of a segmentation fault in Stage's worker threads: its run is made again, and said)
ATTEMPTS = 3


class EndedError(RuntimeError):
    """stageros or the node ended during a run."""


class Bench(stage_bench.Bench):
    """stage_bench's roscore and /clock subscriber; a run is stageros and the node."""

    def run(self, command, world, robots, window_s, env=None, with_node=True):
        """One run: dict of the figures."""
        with self._lock:
            self._clock = None
        master = rosgraph.Master('/swarm_ros_bench')
        for name in ('/stageros', '/swarm_controller'):
            with contextlib.suppress(rosgraph.MasterError):
                master.deleteParam(name)
        master.setParam('/use_sim_time', True)
        start = time.monotonic()
        sim = spawn([*command, '-g', world], env=env, stop_timeout_s=20.0)
        node = spawn([*NODE, '_robots:=%d' % robots] if with_node else ['sleep', '1000000'],
                     stop_timeout_s=20.0)
        try:
            if with_node:
                wait_for(lambda: node.printed(FIRST_SCANS_LINE) or not sim.alive(),
                         START_DEADLINE_S, 'every first scan at the node', alive=node.alive)
            else:
                wait_for(lambda: self.clock() or not sim.alive(), START_DEADLINE_S, '/clock')
            if not sim.alive():
                raise RuntimeError('stageros ended:\n' + sim.tail())
            start_s = time.monotonic() - start
            time.sleep(WARMUP_S)
            sim0, wall0 = wait_for(self.clock, START_DEADLINE_S, '/clock')
            cpu0 = (stage_bench.cpu_s(sim.pid), stage_bench.cpu_s(node.pid))
            time.sleep(window_s)
            sim1, wall1 = self.clock()
            cpu1 = (stage_bench.cpu_s(sim.pid), stage_bench.cpu_s(node.pid))
            rss = (peak_rss_mb(sim.pid), peak_rss_mb(node.pid))
            for proc, who, peak in ((sim, 'stageros', rss[0]), (node, 'the node', rss[1])):
                # its clock or its figures stopped in the window (an ended process's status
                # has no VmHWM)
                if peak is None or not proc.alive():
                    raise EndedError('%s ended during the run:\n%s' % (who, proc.tail()))
            wall = wall1 - wall0
            spreads = [line for line in node.lines() if 'spread' in line]
            return dict(rtf=(sim1 - sim0) / wall, sim_cores=(cpu1[0] - cpu0[0]) / wall,
                        node_cores=(cpu1[1] - cpu0[1]) / wall, sim_rss=rss[0],
                        node_rss=rss[1], start=start_s,
                        spread=spreads[-1].split('spread ')[-1] if spreads else '-')
        finally:
            node.stop()
            sim.stop()


def median(runs):
    out = {k: statistics.median(r[k] for r in runs) for k in runs[0] if k != 'spread'}
    out['spread'] = runs[-1]['spread']
    return out


def measure(bench, sides, path, robots, args):
    """{simulator: median figures} of args.runs runs of each, one simulator at a time."""
    runs = {name: [] for name, _, _ in sides}
    for k in range(args.runs):
        for name, command, env in sides:
            print('bench: %d swarmbots, %s, run %d of %d' % (robots, name, k + 1, args.runs),
                  flush=True)
            for attempt in range(ATTEMPTS):
                try:
                    r = bench.run(command, path, robots, args.window, env,
                                  not args.without_node)
                    break
                except EndedError as died:
                    if attempt == ATTEMPTS - 1:
                        raise SystemExit('bench: %s: %s' % (name, died)) from None
                    print('bench: %s: %s; once more' % (name, str(died).splitlines()[0]),
                          flush=True)
            print('bench:   ' + ', '.join('%s %s' % (key, '%.3g' % v if isinstance(v, float)
                                                     else v) for key, v in r.items()),
                  flush=True)
            runs[name].append(r)
    return {name: median(r) for name, r in runs.items()}


def peer_env(peer, lib):
    lib = lib or os.path.normpath(os.path.join(os.path.dirname(peer), *['..'] * 4,
                                               'install', 'lib'))
    env = {}
    if os.path.isdir(lib):
        env['LD_LIBRARY_PATH'] = lib + ':' + os.environ.get('LD_LIBRARY_PATH', '')
    return env


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--peer', default='/work/scratch/peer/ws/devel/lib/stage_ros/stageros',
                    help="real stageros's executable ('' to skip it)")
    ap.add_argument('--peer-lib', help="real Stage's libraries (LD_LIBRARY_PATH)")
    ap.add_argument('--robots', type=int, nargs='+', default=list(COUNTS))
    ap.add_argument('--runs', type=int, default=RUNS)
    ap.add_argument('--window', type=float, default=WINDOW_S, help='wall s measured')
    ap.add_argument('--only', choices=('stage_lite', 'Stage'), help='one side only')
    ap.add_argument('--without-node', action='store_true',
                    help='stageros alone (nothing subscribed but /clock)')
    args = ap.parse_args(argv)
    sides = [('stage_lite', OURS, None)]
    if args.peer and os.access(args.peer, os.X_OK):
        sides.append(('Stage', [args.peer], peer_env(args.peer, args.peer_lib)))
    elif args.peer:
        print('bench: no real stageros at %s: measuring stage_lite only' % args.peer)
    if args.only:
        sides = [s for s in sides if s[0] == args.only]
    worlds = swarm_world.write_worlds(tempfile.mkdtemp(prefix='swarm_ros_bench_'),
                                      tuple(args.robots), ros=True)
    bench = Bench()
    try:
        rows = [(n, measure(bench, sides, path, n, args)) for n, path in worlds.items()]
    finally:
        bench.close()
    print()
    if args.without_node:
        print('stageros alone (no swarm_controller; node columns: an idle placeholder)')
    print('| robots | simulator | real-time factor | stageros cores | node cores | stageros '
          'peak RSS MB | node peak RSS MB | start to every first scan s | spread m |')
    print('|---|---|---|---|---|---|---|---|---|')
    for n, by_side in rows:
        for name, m in by_side.items():
            print('| %d | %s | %.2f | %.2f | %.2f | %.0f | %.0f | %.2f | %s |'
                  % (n, name, m['rtf'], m['sim_cores'], m['node_cores'], m['sim_rss'],
                     m['node_rss'], m['start'], m['spread']))
        if len(by_side) == 2:
            print('| %d | stage_lite / Stage | %.2f x | | | | | %.2f x | |'
                  % (n, by_side['stage_lite']['rtf'] / by_side['Stage']['rtf'],
                     by_side['stage_lite']['start'] / by_side['Stage']['start']))


if __name__ == '__main__':
    main()
