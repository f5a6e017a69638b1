"""Model-only Stage benchmark: world load, ray casts and motion per step, no ROS.

Run: `/usr/bin/python3 bench/stage_raycast_bench.py [--map PLAN] [--repeats N]` with the devel
space sourced (or PYTHONPATH=src/stage/stage_lite/src). Worlds: the lesson's 4 erratics and
20 / 50 / 100 erratics from bench/make_stage_worlds.py on PLAN (default: the office plan),
every robot turning in place at 0.3 rad/s (stage_bench's load). Each world runs in a fresh
child process so its load time and peak RSS are its own. Per world: load time, steps timed in
REPEATS runs of STEPS steps (median of the runs), of which the ray cast, the model real-time
factor (interval_sim / step time), rays per second, and the process's peak RSS.
"""

import json
import os
import resource
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
STEPS = 50
WARMUP = 5
CHILD_TIMEOUT_S = 900.0  # one world's child: 100 erratics on a loaded machine take minutes


def measure(path, repeats):
    """Runs in the child: one world, printed as one JSON line."""
    t0 = time.perf_counter()
    from stage_lite.model.world import load_world
    w = load_world(path)
    load_s = time.perf_counter() - t0
    for i in range(len(w.robots)):
        w.set_command(i, 0.0, 0.0, 0.3)
    for _ in range(WARMUP):
        w.step()
    steps, casts = [], []
    for _ in range(repeats):
        t = time.perf_counter()
        for _ in range(STEPS):
            w.step()
        steps.append((time.perf_counter() - t) / STEPS)
        t = time.perf_counter()
        for _ in range(STEPS):
            w.cast_rays()
        casts.append((time.perf_counter() - t) / STEPS)
    beams = sum(g.samples for r in w.robots for g in r.rangers)
    print(json.dumps({
        'robots': len(w.robots), 'beams': beams, 'load_s': load_s,
        'step_s': statistics.median(steps), 'cast_s': statistics.median(casts),
        'interval_s': w.interval_sim_s,
        'rss_mb': resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}))


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == '--child':
        measure(argv[1], int(argv[2]))
        return
    plan, repeats = None, 5
    while argv:
        option, value, argv = argv[0], argv[1], argv[2:]
        if option == '--map':
            plan = value
        elif option == '--repeats':
            repeats = int(value)
        else:
            raise SystemExit('usage: stage_raycast_bench.py [--map PLAN] [--repeats N]')
    # Here, not at the top: the children import only the model, so their peak RSS is its own.
    from course_common.processes import run_to_exit
    sys.path.insert(0, HERE)
    import make_stage_worlds
    with tempfile.TemporaryDirectory() as tmp:
        made = make_stage_worlds.write_worlds(tmp, (4, 20, 50, 100),
                                              plan or make_stage_worlds.OFFICE)
        worlds = [('the lesson' if n == 4 else '%d erratics' % n, p)
                  for n, p in sorted(made.items())]
        print('| world | robots | beams | load s | step ms | of which rays ms | real-time factor'
              ' | Mrays/s | peak RSS MB |')
        print('|---|---|---|---|---|---|---|---|---|')
        for name, path in worlds:
            code, out = run_to_exit([sys.executable, __file__, '--child', path, str(repeats)],
                                    CHILD_TIMEOUT_S)
            if code != 0:
                raise SystemExit('%s: the measuring child failed (%s):\n%s' % (name, code, out))
            r = json.loads(out.strip().splitlines()[-1])
            print('| %s | %d | %d | %.2f | %.1f | %.1f | %.1f | %.1f | %.0f |' % (
                name, r['robots'], r['beams'], r['load_s'], r['step_s'] * 1e3,
                r['cast_s'] * 1e3, r['interval_s'] / r['step_s'],
                r['beams'] / r['cast_s'] / 1e6, r['rss_mb']))


if __name__ == '__main__':
    main()
