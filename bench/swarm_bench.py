"""Swarms: Stage's benchmark swarmbot, 1 to 100,000 of them, stage_lite's `stage -g` beside
the real Stage's, and beside Vaughan's linear law.

    ./ws bench swarm_bench [--peer STAGE] [--counts N ..] [--runs K] [--ours COMMAND]

The worlds are stage_lite.swarm_world's (Stage's benchmark swarmbot with its expand_swarm
controller, 12 infrared rangers of 2 m; the hospital's 140 m x 60 m floor as a tile per
1,000 robots, open; 0.02 m grid, as hospital.world), written to a temporary folder. Each
simulator runs each world to two quit times T1 < T2 (SPANS) under /usr/bin/time, one run at
a time, in turn; as in stage_worlds_bench:
* wall s per simulated s = (wall(T2) - wall(T1)) / (T2 - T1), and the real-time factor;
* cores: (user + sys) over the same difference of wall time;
* start-up: wall(T1) less T1's simulated seconds at that rate (loading the world, starting
  the controllers);
* peak RSS of the T2 run, and per robot: (RSS(N) - RSS(1)) / N, what one more robot costs.
Medians of RUNS (default 3). The real Stage is STAGE (default the peer built beside,
/work/scratch/peer/install/bin/stage, its libstage through LD_LIBRARY_PATH=<prefix>/lib);
without it only stage_lite runs. Vaughan's law: Stage 2008's measured curve, about 1,000
simple robots at real time and linear in N (Vaughan, "Massively multi-robot simulation in
Stage", Swarm Intelligence 2008): N / 1000 wall s per simulated s on its machine, given as
the line the others are read against.
"""
import argparse
import os
import shlex
import statistics
import sys
import tempfile

from stage_lite import swarm_world
from stage_worlds_bench import PEER, run, timed_copy  # the bench beside this one

RUNS = 3
COUNTS = (1, 10, 100, 1000, 10000)
#: N: (T1, T2) simulated s: T2 - T1 about a second of wall time or more on the slower one
SPANS = {1: (10, 2010), 10: (10, 1010), 100: (5, 205), 1000: (2, 32), 10000: (1, 6),
         100000: (1, 11)}
VAUGHAN_ROBOTS_AT_REAL_TIME = 1000


def span_of(n):
    """(T1, T2) for n robots: the listed count at or above n."""
    return SPANS[min((k for k in SPANS if k >= n), default=max(SPANS))]


#: runs of a world in a row before the bench gives up on it (the real Stage 4.3.0 now and then
#: dies of a segmentation fault in its worker threads: its run is made again, and counted)
ATTEMPTS = 3
CRASHES = []


def run_again_if_it_crashes(command, world, env):
    """run(), made again when the simulator dies (up to ATTEMPTS), each death counted."""
    for attempt in range(ATTEMPTS):
        try:
            return run(command, world, env)
        except SystemExit as failed:
            if attempt == ATTEMPTS - 1:
                raise
            exit_line = str(failed).splitlines()[0]
            CRASHES.append('%s on %s (%s)' % (os.path.basename(command[0]),
                                              os.path.basename(world),
                                              exit_line[exit_line.rfind('(') + 1:].rstrip('):')))
            print('bench: %s, made again' % CRASHES[-1], flush=True)
    return None


def measure(command, world_dir, n, env):
    """One pair of runs: (wall s per simulated s, cores, start-up s, peak RSS MB)."""
    t1, t2 = span_of(n)
    path = os.path.basename(os.path.join(world_dir, 'swarm_%d.world' % n))
    wall0, cpu0, _ = run_again_if_it_crashes(command, timed_copy(world_dir, path, t1), env)
    wall1, cpu1, rss = run_again_if_it_crashes(command, timed_copy(world_dir, path, t2), env)
    rate = max(wall1 - wall0, 1e-3) / (t2 - t1)
    return rate, (cpu1 - cpu0) / max(wall1 - wall0, 1e-3), max(wall0 - t1 * rate, 0.0), rss


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--peer', default=PEER, help="the real Stage's program")
    ap.add_argument('--counts', type=int, nargs='+', default=list(COUNTS),
                    help='robot counts (default %s; 100000 takes minutes)'
                    % ' '.join(map(str, COUNTS)))
    ap.add_argument('--runs', type=int, default=RUNS)
    ap.add_argument('--ours', default='stage', help="stage_lite's program (a command line)")
    args = ap.parse_args(argv)
    if any(n < 1 for n in args.counts):
        ap.error('a swarm needs at least one robot')
    sides = []
    if os.access(args.peer, os.X_OK):
        sides.append(('Stage', [args.peer], dict(os.environ, LD_LIBRARY_PATH=os.path.join(
            os.path.dirname(os.path.dirname(os.path.abspath(args.peer))), 'lib'))))
    else:
        print('swarm_bench: the real Stage is not at %s (--peer): stage_lite alone'
              % args.peer)
    sides.append(('stage_lite', shlex.split(args.ours), dict(os.environ)))
    counts = sorted(set(args.counts) | {1})
    got = {}
    with tempfile.TemporaryDirectory(prefix='swarm_bench_') as tmp:
        swarm_world.write_worlds(tmp, counts)
        for n in counts:
            runs = {side: [] for side, _, _ in sides}
            for k in range(args.runs):
                for side, command, env in sides:
                    print('bench: %d swarmbots, %s, run %d of %d' % (n, side, k + 1,
                                                                     args.runs), flush=True)
                    runs[side].append(measure(command, tmp, n, env))
            got[n] = {side: tuple(statistics.median(r[i] for r in rs) for i in range(4))
                      for side, rs in runs.items()}
    print()
    print('| swarmbots | simulator | wall ms per simulated s | real-time factor | vs Stage |'
          ' cores | start-up s | peak RSS MB | KB per robot | Vaughan\'s law, ms |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for n in counts:
        if n not in args.counts:
            continue
        for side, _, _ in sides:
            rate, cores, start, rss = got[n][side]
            per_robot = (rss - got[1][side][3]) * 1024 / n if n > 1 else float('nan')
            real = got[n].get('Stage')
            print('| %d | %s | %.1f | %.2f | %s | %.2f | %.1f | %.0f | %s | %.0f |' % (
                n, side, rate * 1e3, 1 / rate,
                '' if side == 'Stage' or real is None else '**%.2f x**' % (real[0] / rate),
                cores, start, rss, '' if n == 1 else '%.1f' % per_robot,
                n / VAUGHAN_ROBOTS_AT_REAL_TIME * 1e3))
    if CRASHES:
        print('\nRuns made again after the simulator died (%d): %s'
              % (len(CRASHES), '; '.join(CRASHES)))


if __name__ == '__main__':
    sys.exit(main())
