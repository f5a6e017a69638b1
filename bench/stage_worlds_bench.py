"""Stage's own program on Stage's own worlds: stage_lite's `stage -g` beside the real Stage's.

    ./ws bench stage_worlds_bench [--peer STAGE] [--worlds DIR] [--runs N] [--only NAME ..]
                                  [--ours COMMAND] [--before COMMAND]
                                  [--world PATH [PATH ..]] [--span T1 T2]

STAGE is the real Stage 4.3.0's program (default /work/scratch/peer/install/bin/stage, its
libstage found through LD_LIBRARY_PATH=<its prefix>/lib), DIR a copy of Stage's `worlds/`
folder (default /work/scratch/worlds, with `benchmark/`; its NAME_run.world are NAME.world
with `paused 0`, as the golden captures name them, which each timed copy sets anyway);
without either the bench says what is missing and skips (exit 0). stage_lite's is `stage`
from the sourced workspace (or --ours, a command line); --before adds another stage_lite to
the rotation (a command line running an earlier tree, say), to compare before and after in
one run.

The worlds (WORLDS): simple (two wanderers), autolab_run (wanderers on Stage's autolab
plan), pioneer_flocking_run (100 pioneers, sonars and fiducial finders), SFU_run (94 such
flockers on Stage's SFU plan), fasr2 (100 foragers planning with A*, power packs and
chargers), benchmark/cave (100 pioneers with sonars and lasers, expand_pioneer; its `paused
1` turned to 0) and
benchmark/hospital (1000 swarmbots, 12 IR rangers each, expand_swarm). Each is copied twice
into a folder that mirrors DIR (links to its includes and bitmaps), with `quit_time` T1 and
T2; `stage -g` runs each copy to its quit_time under /usr/bin/time, and the difference of
the two runs is what the simulated seconds between T1 and T2 cost, loading and start-up
left out:
* wall s per simulated s = (wall(T2) - wall(T1)) / (T2 - T1), and the real-time factor;
* cores = (user + sys)(T2) - (user + sys)(T1) over the same wall difference;
* peak RSS (MB) of the T2 run.
--world adds worlds of your own (self-contained files, such as bench/make_swarm_worlds.py's,
copied into the bench's folder), each run between --span's T1 and T2 (default 2 and 12 s).
RUNS times (default 3), each simulator in turn, one at a time; medians of the runs. Prints
a markdown table, a row per world and simulator, with the ratio of each real-time factor to
the real Stage's (above 1: faster than Stage).
"""
import argparse
import os
import re
import shlex
import statistics
import subprocess
import sys
import tempfile

RUNS = 3
PEER = '/work/scratch/peer/install/bin/stage'
WORLDS_DIR = '/work/scratch/worlds'
#: (name, world file under DIR, T1 s, T2 s): T2 - T1 long enough for a second of wall time
#: or more on the slower simulator, short enough for the whole bench to take minutes
WORLDS = (('simple', 'simple.world', 10, 310),
          ('autolab', 'autolab_run.world', 5, 35),
          ('pioneer_flocking', 'pioneer_flocking_run.world', 5, 45),
          ('SFU', 'SFU_run.world', 5, 905),     # Stage's load (4.8 GB, 25 s) swings by 3 s
          ('fasr2', 'fasr2.world', 5, 35),
          ('cave', 'benchmark/cave.world', 5, 35),
          ('hospital', 'benchmark/hospital.world', 2, 12))
SPAN_S = (2, 12)       # --world's T1 and T2: the hospital's span
TIME_FORMAT = 'bench-time %e %U %S %M'
RUN_TIMEOUT_S = 1800.0
CRASH_RETRIES = 2


def mirror(src, dst):
    """dst: a folder of links to src's entries, its sub-folders mirrored the same way."""
    os.makedirs(dst, exist_ok=True)
    for name in os.listdir(src):
        path = os.path.join(src, name)
        if os.path.isdir(path) and not os.path.islink(path):
            mirror(path, os.path.join(dst, name))
        else:
            os.symlink(path, os.path.join(dst, name))


def own_copy(path, dest):
    """A copy of the world file at path as dest, a file of its own: where the mirror has a
    link of that name (one of Stage's worlds), the link goes first, so that the copy never
    writes through it into the worlds folder."""
    with open(path, 'rb') as src:
        text = src.read()
    if os.path.lexists(dest):
        os.unlink(dest)
    with open(dest, 'wb') as f:
        f.write(text)


def timed_copy(root, world, quit_time_s):
    """A copy of root/world beside it (a new file), running from the start and quitting at
    quit_time_s; its path."""
    path = os.path.join(root, world)
    with open(path, encoding='latin-1') as f:
        text = f.read()
    text = re.sub(r'(?m)^\s*quit_time\b.*$', '', text)
    text = re.sub(r'(?m)^(\s*)paused\s+1\b', r'\1paused 0', text)
    stem, ext = os.path.splitext(path)
    out = '%s_bench_q%d%s' % (stem, quit_time_s, ext)
    with open(out, 'w', encoding='latin-1') as f:
        f.write(text + '\nquit_time %d\n' % quit_time_s)
    return out


def run(command, world, env):
    """`command -g world` to its quit_time: (wall s, cpu s, peak RSS MB). A run killed by a
    signal is run again (up to CRASH_RETRIES times): the real Stage's World::Raytrace race
    segfaults now and then on worlds with `threads` > 1 (fasr2, SFU, hospital)."""
    args = ['/usr/bin/time', '-f', TIME_FORMAT, *command, '-g', os.path.basename(world)]
    for _ in range(CRASH_RETRIES + 1):
        done = subprocess.run(args, cwd=os.path.dirname(world), env=env, capture_output=True,
                              text=True, timeout=RUN_TIMEOUT_S, check=False)
        if 'terminated by signal' not in done.stderr:    # /usr/bin/time's line
            break
        print('bench: %s on %s crashed, once more' % (command[0], world), flush=True)
    lines = [line for line in done.stderr.splitlines() if line.startswith('bench-time ')]
    if done.returncode != 0 or not lines:
        raise SystemExit('%s on %s failed (exit %s):\n%s' % (
            ' '.join(command), world, done.returncode, done.stderr[-2000:]))
    wall, user, system, rss_kb = (float(v) for v in lines[-1].split()[1:])
    return wall, user + system, rss_kb / 1024.0


def measure(command, short, long_, span_s, env):
    """One run of each copy: (wall s per simulated s, cores, peak RSS MB), or None when the
    longer run did not take longer (start-up's swing larger than the span's cost)."""
    wall0, cpu0, _ = run(command, short, env)
    wall1, cpu1, rss = run(command, long_, env)
    wall = wall1 - wall0
    if wall <= 0.0:
        print('bench: %s: %s took %.2f s, %s %.2f s: not counted' % (
            command[0], os.path.basename(long_), wall1, os.path.basename(short), wall0),
            flush=True)
        return None
    return wall / span_s, (cpu1 - cpu0) / wall, rss


def missing(peer, worlds_dir):
    """What stops the bench, or None."""
    if not os.access(peer, os.X_OK):
        return 'the real Stage is not at %s (--peer)' % peer
    for _, world, _, _ in WORLDS:
        if not os.path.isfile(os.path.join(worlds_dir, world)):
            return "Stage's world %s is not in %s (--worlds)" % (world, worlds_dir)
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--peer', default=PEER, help="the real Stage's program")
    ap.add_argument('--worlds', default=WORLDS_DIR, help="a copy of Stage's worlds/ folder")
    ap.add_argument('--runs', type=int, default=RUNS)
    ap.add_argument('--only', nargs='+', choices=[w[0] for w in WORLDS],
                    help='these worlds only')
    ap.add_argument('--ours', default='stage', help="stage_lite's program (a command line)")
    ap.add_argument('--before', help='an earlier stage_lite, measured beside (a command line)')
    ap.add_argument('--world', nargs='+', default=[],
                    help='world files of your own, self-contained (run with --span)')
    ap.add_argument('--span', nargs=2, type=int, default=SPAN_S, metavar=('T1', 'T2'),
                    help="--world's quit times (s)")
    args = ap.parse_args(argv)
    why = missing(args.peer, args.worlds)
    if why:
        print('stage_worlds_bench: skipped: %s' % why)
        return
    peer_env = dict(os.environ, LD_LIBRARY_PATH=os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(args.peer))), 'lib'))
    sides = [('Stage', [args.peer], peer_env)]
    if args.before:
        sides.append(('stage_lite before', shlex.split(args.before), dict(os.environ)))
    sides.append(('stage_lite', shlex.split(args.ours), dict(os.environ)))
    rows = []
    with tempfile.TemporaryDirectory(prefix='stage_worlds_bench_') as tmp:
        mirror(args.worlds, tmp)
        own = []
        for path in args.world:          # beside Stage's worlds, under the bench's folder
            name = os.path.splitext(os.path.basename(path))[0]
            own_copy(path, os.path.join(tmp, name + '.world'))
            own.append((name, name + '.world', *args.span))
        chosen = [w for w in WORLDS if (args.only or not own) and (not args.only
                                                                  or w[0] in args.only)]
        for name, world, t1, t2 in chosen + own:
            short, long_ = timed_copy(tmp, world, t1), timed_copy(tmp, world, t2)
            runs = {side: [] for side, _, _ in sides}
            for k in range(args.runs):
                for side, command, env in sides:     # one simulator at a time, in turn
                    print('bench: %s, %s, run %d of %d' % (name, side, k + 1, args.runs),
                          flush=True)
                    got = measure(command, short, long_, t2 - t1, env)
                    if got is not None:
                        runs[side].append(got)
            rows.append((name, {side: tuple(statistics.median(r[i] for r in got)
                                            for i in range(3)) if got else None
                                for side, got in runs.items()}))
    print()
    print('| world | simulator | wall ms per simulated s | real-time factor | vs Stage | cores |'
          ' peak RSS MB |')
    print('|---|---|---|---|---|---|---|')
    for name, by in rows:
        real = by['Stage'][0] if by['Stage'] else None
        for side, _, _ in sides:
            if by[side] is None:
                print('| %s | %s | no run counted | | | | |' % (name, side))
                continue
            wall, cores, rss = by[side]
            versus = '' if side == 'Stage' or real is None else '**%.2f x**' % (real / wall)
            print('| %s | %s | %.1f | %.2f | %s | %.2f | %.0f |' % (
                name, side, wall * 1e3, 1 / wall, versus, cores, rss))


if __name__ == '__main__':
    sys.exit(main())
