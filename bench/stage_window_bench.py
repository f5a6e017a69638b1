"""What stageros's window costs: the lesson with and without it, at real time and flat out.

    ./ws bench stage_window_bench [--runs N]

The lesson's own world (stage_multi's willow-multi-erratic.world: its 745 x 448 view at
28.8 px/m, four erratics with 1081-beam lasers), stage_lite's stageros started by
stage_bench's Bench (its own roscore, the watchdog off, every robot turning in place so that
every frame has something new to draw), in turn RUNS times (default 3): headless (-g) and
with the window on an Xvfb display,
* at real time (~speedup 1): the cores the process uses over REAL_TIME_WINDOW_S;
* flat out (~speedup -1): the real-time factor, which the window must not lower much (it
  draws at its own 10 frames a second from a snapshot, dropping frames rather than steps).
Medians of the runs; prints a markdown table and the window's extra cores at real time.
"""
import argparse
import statistics

import stage_bench  # bench/ is on sys.path: ./ws bench runs the files from there
from course_common.testing import Xvfb

from stage_multi import lesson_world

RUNS = 3
ROBOTS = len(lesson_world.STARTS)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--runs', type=int, default=RUNS)
    args = ap.parse_args(argv)
    world = lesson_world.world_path()
    modes = (('real time', ['_speedup:=1'], stage_bench.REAL_TIME_WINDOW_S),
             ('flat out', ['_speedup:=-1'], stage_bench.WINDOW_S))
    results = {(mode, gui): [] for mode, _, _ in modes for gui in (False, True)}
    bench = stage_bench.Bench()
    try:
        with Xvfb(stage_bench.XVFB_SCREEN) as xvfb:
            for k in range(args.runs):
                for mode, extra, window_s in modes:
                    for gui in (False, True):     # one at a time, in turn
                        print('bench: %s, %s, run %d of %d'
                              % (mode, 'window' if gui else 'headless', k + 1, args.runs),
                              flush=True)
                        results[(mode, gui)].append(bench.run(
                            stage_bench.OURS, world, ROBOTS, extra, gui=gui,
                            env={'DISPLAY': xvfb.display} if gui else None,
                            window_s=window_s))
    finally:
        bench.close()
    med = {key: [statistics.median(r[i] for r in runs) for i in range(3)]
           for key, runs in results.items()}
    print()
    print('| the lesson (stage_lite) | real-time factor | cores | peak RSS MB |')
    print('|---|---|---|---|')
    for mode, _, _ in modes:
        for gui in (False, True):
            rtf, cores, rss = med[(mode, gui)]
            print('| %s, %s | %.2f | %.3f | %.0f |'
                  % (mode, 'window (Xvfb)' if gui else 'headless', rtf, cores, rss))
    extra = med[('real time', True)][1] - med[('real time', False)][1]
    slowed = med[('flat out', True)][0] / med[('flat out', False)][0]
    print()
    print('the window at real time: +%.3f core; flat out with the window: %.2f x the headless '
          'real-time factor' % (extra, slowed))


if __name__ == '__main__':
    main()
