"""stage_lite on Stage 4.3.0's own worlds, held to the real Stage's runs of them, no ROS.

Run: `./ws bench stage_worlds_fidelity --worlds STAGE/worlds [--seconds S] [--seed N ..]
[--runs N] [--own-seeds]
[WORLD ...]` with STAGE/worlds a copy of Stage v4.3.0's worlds/ folder (GPL-2, not in this
repository: see src/stage/stage_lite/test/golden/stage_worlds/README.md); without it the
bench says so and does nothing. For each world with golden data (stage_worlds/<world>.npz,
the real Stage's own runs), stage_lite runs it as `stage -g` does, in Stage's model order
(model_order.json, read from a real run), seeded with N (load_world's seed: random()'s and
drand48's streams; default none, an unseeded process's, as Stage's random() is), for S
simulated seconds (default: as long as the real runs, at most 60 s), and prints per world
(and per seed, several seeds being several runs):
- where the real runs part from each other and where stage_lite parts from each real run,
  by one rule: the first state at which a robot's x, y or heading differ by more than 1e-9
  (m, rad), over the first 100 states the golden data keeps at float64 (the golden data's
  own parting_state looks at x and y alone: in the flocking worlds the runs' headings part
  one state before their positions);
- per swarm statistic (path length, moving share, speed; alignment and spacing when
  flocking; for the foraging worlds the mean distance to the nearest source and sink and
  the flags delivered per sink, also every minute), at how many of the one-second times
  stage_lite lies within the real runs' min..max, and the figures at the last time; beside
  it, how a real run fits the others (each run held to the other runs' min..max: the median
  and the least of its counts), which is what "within the real runs' spread" can ask of a run;
- load and run times (on a machine shared with nothing else, this is also a speed figure).
With --runs N, stage_lite makes N runs of each world as the real Stage makes its runs
(load_world's run: what Stage draws from the clock and its race, random() left unseeded),
and a last row gives, per statistic, the median and least of its counts beside a real run's.
With --own-seeds, stage_lite also runs with each real run's clock second (the second Stage
seeded drand48 with, which the capture recorded: load_world's run) and a row gives the state
at which it first differs from that run.
With --no-race, every ranger casts after the moves (stage_lite without its model of Stage's
worker-thread race, race.py), for a side-by-side comparison.
"""
import argparse
import contextlib
import json
import os
import sys
import time

GOLDEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'src', 'stage',
                      'stage_lite', 'test', 'golden', 'stage_worlds')
#: the world file for each golden world, in Stage's worlds/ (the paused ones run all the same:
#: Stage's headless World reads no `paused`)
FILES = {'benchmark_cave': 'benchmark/cave.world', 'benchmark_hospital': 'benchmark/hospital.world'}
FLOCKING = ('pioneer_flocking', 'SFU')
PREFIX_TOL_M = 1e-9
MAX_SECONDS = 60.0


def first_difference(ours, real):
    """The first state at which two (T, N, 3) pose arrays differ by more than the tolerance
    (headings compared on the circle); None if never."""
    import numpy as np
    e = np.abs(ours - real)
    e[..., 2] = np.abs((ours[..., 2] - real[..., 2] + np.pi) % (2 * np.pi) - np.pi)
    apart = e.max(axis=(1, 2)) > PREFIX_TOL_M
    return int(np.argmax(apart)) if apart.any() else None


def runs_part(prefix):
    """The first state at which the real runs (R, T, N, 3) are not all the same
    (first_difference's rule), None if never."""
    parts = [s for s in (first_difference(prefix[0], prefix[r]) for r in range(1, len(prefix)))
             if s is not None]
    return min(parts) if parts else None


@contextlib.contextmanager
def golden_world(world, folder, **kw):
    """stage_lite's World of a golden world from Stage's worlds/ `folder`, as `stage -g`
    loads it, in Stage's model order (load_world's other keywords: kw), the world file's
    folder the working directory meanwhile (worlds name their .inc and bitmaps from it)."""
    from stage_lite.model.world import load_world
    with open(os.path.join(GOLDEN, 'model_order.json')) as f:
        order = json.load(f)[world]
    path = os.path.join(folder, FILES.get(world, world + '.world'))
    here = os.getcwd()
    os.chdir(os.path.dirname(path))
    try:
        yield load_world(os.path.basename(path), stageros=False, model_order=order, **kw)
    finally:
        os.chdir(here)


def own_seed_partings(world, folder, race=True):
    """Per real run, the state at which stage_lite, run with that run's clock second
    (load_world's run: Stage's srand48(time(NULL)), and fasr2's srandom), first differs
    from it (first_difference), over the golden data's float64 prefix."""
    import numpy as np
    data = np.load(os.path.join(GOLDEN, world + '.npz'))
    meta = json.loads(str(data['meta']))
    prefix = data['prefix_pose']
    out = []
    for r, second in enumerate(meta['seeds']):
        with golden_world(world, folder, race=race, run=second) as w:
            poses = [[x.pose for x in w.robots]]
            for _ in range(prefix.shape[1] - 1):
                w.step()
                poses.append([x.pose for x in w.robots])
        out.append(first_difference(np.array(poses), prefix[r]))
    return out


def check(world, folder, seconds, seed=None, race=True, run=None):
    """One world's line of figures (a dict)."""
    import numpy as np
    from stage_lite.testing import swarm_stats
    data = np.load(os.path.join(GOLDEN, world + '.npz'))
    meta = json.loads(str(data['meta']))
    dt = meta['interval_sim_us'] / 1e6
    steps = int(round(min(seconds, (meta['states'] - 1) * dt) / dt))
    t0 = time.perf_counter()
    with golden_world(world, folder, seed=seed, race=race, run=run) as w:
        load_s = time.perf_counter() - t0
        sinks = [m for m in w.models if m.parent is None and m.token.endswith('sink')]
        poses = [[r.pose for r in w.robots]]
        held = [[len(m.flags) for m in sinks]]
        t0 = time.perf_counter()
        for _ in range(steps):
            w.step()
            poses.append([r.pose for r in w.robots])
            held.append([len(m.flags) for m in sinks])
        run_s = time.perf_counter() - t0
    poses = np.array(poses)
    prefix = data['prefix_pose']
    n = min(prefix.shape[1], poses.shape[0])
    t_s = np.arange(poses.shape[0]) * dt
    times = np.array([t for t in data['stat_t_s'].astype(float) if t <= t_s[-1] + 1e-9])
    places = {k: np.array(v) for k, v in meta.get('places', {}).items()}
    ours = swarm_stats.swarm_stats(t_s, poses, times, flocking=world in FLOCKING,
                                   places=places)
    if places and sinks:     # what each sink holds beyond its start, as make_golden.py counts
        held = np.array(held)
        idx = swarm_stats.state_index(t_s, times)
        ours['delivered_per_sink'] = (held[idx] - held[:1]).mean(axis=1)
    stats = {}
    course = []
    for name, values in ours.items():
        key = 'stat_' + name
        if name == 't_s' or key not in data.files:
            continue
        real = data[key][:, :len(times)].astype(float)
        lo, hi = real.min(axis=0), real.max(axis=0)
        inside = swarm_stats.within_runs(values, real)
        real_fit = swarm_stats.runs_within_the_others(real)
        stats[name] = (int(inside.sum()), len(inside), float(values[-1]), float(lo[-1]),
                       float(hi[-1]), float(np.median(real_fit)), int(real_fit.min()))
        if name == 'delivered_per_sink':     # deliveries come late: the whole course
            course = [(t, values[i], lo[i], hi[i]) for i, t in enumerate(times)
                      if t > 0 and t % 60 == 0]
    return dict(world=world, robots=len(w.robots), course=course,
                runs=int(prefix.shape[0]),
                real_parting=runs_part(prefix),
                ours=[first_difference(poses[:n], prefix[r, :n]) for r in range(prefix.shape[0])],
                prefix=n - 1, seconds=steps * dt, load_s=load_s, run_s=run_s, stats=stats)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--worlds', help="a copy of Stage v4.3.0's worlds/ folder")
    parser.add_argument('--seconds', type=float, default=MAX_SECONDS)
    parser.add_argument('--seed', type=int, nargs='+', default=[None],
                        help="the worlds' seed; several: a run each (default: none)")
    parser.add_argument('--runs', type=int, default=0,
                        help="stage_lite's runs 1..N as the real Stage's (load_world's run)")
    parser.add_argument('--own-seeds', action='store_true',
                        help="also run stage_lite with each real run's clock second")
    parser.add_argument('--no-race', action='store_true',
                        help="every ranger casts after the moves (no model of Stage's race)")
    parser.add_argument('names', nargs='*', help='worlds (default: every golden one)')
    args, _ = parser.parse_known_args(argv)   # ./ws bench passes other benches' options too
    if not args.worlds or not os.path.isdir(args.worlds):
        print("stage_worlds_fidelity: no --worlds folder (Stage v4.3.0's worlds/, not in this "
              'repository): nothing to compare')
        return
    from stage_lite.model.world import WorldError
    with open(os.path.join(GOLDEN, 'model_order.json')) as f:
        known = sorted(json.load(f))
    names = args.names or known
    if args.runs < 0:
        sys.exit('--runs must be 0 or more')
    unknown = sorted(set(names) - set(known))
    if unknown:
        sys.exit('unknown world %s (golden ones: %s)' % (', '.join(unknown), ', '.join(known)))
    print('| world | robots | real runs part at step | stage_lite first differs at step (per'
          ' run) | statistics within the real runs\' range (times; a real run within the'
          ' others\': median, least) | run: sim s, wall s |')
    print('|---|---|---|---|---|---|')
    variants = ([('run %d' % k, dict(run=k)) for k in range(1, args.runs + 1)] if args.runs
                else [('' if seed is None else 'seed %d' % seed, dict(seed=seed))
                      for seed in args.seed])
    for world in names:
        counts = {}
        for label, kw in variants:
            try:
                r = check(world, args.worlds, args.seconds, race=not args.no_race, **kw)
            except WorldError as err:    # a world stage_lite cannot run: say so, go on
                print('| %s | | | not run: %s | | |' % (world, err), flush=True)
                break
            print_line(r, label)
            for name, v in r['stats'].items():
                counts.setdefault(name, []).append(v[0])
        if len(variants) > 1 and counts:
            print_runs(world, len(variants), counts, r['stats'])
        if args.own_seeds:
            parts = own_seed_partings(world, args.worlds, race=not args.no_race)
            print('| %s, each run\'s clock second | | | %s | | |' % (world, ', '.join(
                'never' if p is None else str(p) for p in parts)), flush=True)


def print_runs(world, n, counts, stats):
    """A world's runs together: per statistic the median and least of stage_lite's counts,
    beside a real run's within the others'."""
    import numpy as np
    print('| %s, %d runs | | | | %s | |' % (world, n, '; '.join(
        '%s median %g, least %d (a real run: %g, %d)'
        % (name, np.median(c), min(c), stats[name][5], stats[name][6])
        for name, c in counts.items())), flush=True)


def print_line(r, label):
    """One world's run as a row of the table (and its deliveries' course, if any)."""
    ours = ', '.join('never (of %d)' % r['prefix'] if s is None else str(s) for s in r['ours'])
    stats = '; '.join('%s %d/%d (%.3g in %.3g..%.3g; real %g, %d)' % (k, *v)
                      for k, v in r['stats'].items())
    name = '%s, %s' % (r['world'], label) if label else r['world']
    print('| %s | %d | %s | %s | %s | %.0f s in %.1f s (load %.1f s) |'
          % (name, r['robots'], r['real_parting'], ours, stats, r['seconds'], r['run_s'],
             r['load_s']), flush=True)
    if r['course']:
        print('|  | flags delivered per sink at %s |' % ', '.join(
            '%.0f s: %.3g (real %.3g..%.3g)' % c for c in r['course']), flush=True)


if __name__ == '__main__':
    main()
