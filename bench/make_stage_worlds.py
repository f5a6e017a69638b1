"""Writes Stage worlds of N erratics (the lesson's robot and 1081-beam laser) on a floor plan.

Run: `/usr/bin/python3 bench/make_stage_worlds.py [--map PLAN] [OUT_DIR] [N ...]` with the
devel space sourced (or PYTHONPATH=src/stage/stage_lite/src); defaults: the workspace's
office plan, OUT_DIR build/stage_worlds, N = 4 20 50 100. Prints the paths written. PLAN is
any floor plan of the lesson's size and place (stage_ros's willow-full.pgm, say, which is
the lesson's original: it is not in this repository).

The worlds copy the lesson's (src/stage_multi/world/willow-multi-erratic.world: resolution,
interval_sim, the floor plan's size and pose, the erratic and topurg definitions) and stand
the robots on free floor at least 1.2 m from every wall and from each other, chosen
deterministically (a fixed-seed shuffle of the free places), each with a fixed-seed yaw. The
4-robot world keeps the lesson's own four robots instead. The floor plan is named by
absolute path, so the worlds load from any folder.
"""

import math
import os
import sys
import tempfile

import numpy as np
from scipy.ndimage import distance_transform_edt
from stage_lite.model.world import load_world

from stage_multi import lesson_world

HERE = os.path.dirname(os.path.abspath(__file__))
LESSON = lesson_world.world_path()
WORLD_DIR = os.path.dirname(LESSON)
CLEARANCE_M = 1.2       # from walls and between robot centres (the figure)
CELL_M = 0.1            # candidate places on a 10 cm lattice
SEED = 20140            # fixed: the same worlds on every machine
COLORS = ('blue', 'red', 'green', 'magenta', 'cyan', 'orange', 'purple', 'yellow', 'brown',
          'black')


OFFICE = os.path.join(WORLD_DIR, 'office.pgm')


def free_places(count, floor_plan=OFFICE, seed=SEED):
    """`count` (x, y, yaw) on the floor plan, >= CLEARANCE_M from walls and apart."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, 'plan.world')
        with open(path, 'w') as f:
            f.write(world_text([], floor_plan))
        w = load_world(path)
    occ, ox, oy, res = w.occupancy()
    k = max(1, int(round(CELL_M / res)))
    rows, cols = occ.shape[0] // k, occ.shape[1] // k
    coarse = occ[:rows * k, :cols * k].reshape(rows, k, cols, k).any(axis=(1, 3))
    # distance from a coarse cell's centre to the nearest occupied coarse cell, minus the
    # half-diagonal of a cell: a lower bound of the clearance in metres
    dist = distance_transform_edt(~coarse) * k * res - k * res * math.sqrt(2) / 2
    # only places inside the building: not the margin the grid keeps round the outer wall
    inside = np.zeros_like(coarse)
    filled = np.flatnonzero(coarse.any(axis=1))
    filled_c = np.flatnonzero(coarse.any(axis=0))
    inside[filled[0]:filled[-1] + 1, filled_c[0]:filled_c[-1] + 1] = True
    cand = np.argwhere((dist >= CLEARANCE_M) & inside)
    rng = np.random.default_rng(seed)
    cand = cand[rng.permutation(len(cand))]
    chosen = []
    for r, c in cand:
        x = ox + (c + 0.5) * k * res
        y = oy + (r + 0.5) * k * res
        if all(math.hypot(x - px, y - py) >= CLEARANCE_M for px, py, _ in chosen):
            chosen.append((x, y, float(rng.uniform(-180.0, 180.0))))
            if len(chosen) == count:
                return chosen
    raise RuntimeError('only %d places with %.1f m clearance' % (len(chosen), CLEARANCE_M))


def world_text(places, floor_plan=OFFICE):
    """The lesson's world on `floor_plan` with erratics at `places` (the lesson's own four
    robots when places is None)."""
    with open(LESSON) as f:
        lesson = f.read()
    cut = lesson.index('# throw in a robot')
    head = lesson[:cut].replace('bitmap "office.pgm"', 'bitmap "%s"'
                                % os.path.abspath(floor_plan))
    if places is None:
        return head + lesson[cut:]
    lines = [head, '# %d erratics (bench/make_stage_worlds.py)\n' % len(places)]
    for i, (x, y, yaw) in enumerate(places):
        lines.append('erratic( pose [ %.2f %.2f 0 %.1f ] name "robot%d" color "%s")\n'
                     % (x, y, yaw, i, COLORS[i % len(COLORS)]))
    return ''.join(lines)


def write_worlds(out_dir, counts=(4, 20, 50, 100), floor_plan=OFFICE):
    """Writes <plan>_<N>.world for each N; returns {N: path}."""
    os.makedirs(out_dir, exist_ok=True)
    places = free_places(max(counts), floor_plan)
    name = os.path.splitext(os.path.basename(floor_plan))[0]
    out = {}
    for n in counts:
        path = os.path.join(out_dir, '%s_%d.world' % (name, n))
        with open(path, 'w') as f:
            f.write(world_text(None if n == 4 else places[:n], floor_plan))
        out[n] = path
    return out


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    floor_plan = OFFICE
    if argv[:1] == ['--map']:
        floor_plan = argv[1]
        argv = argv[2:]
    out_dir = argv[0] if argv else os.path.join(HERE, '..', 'build', 'stage_worlds')
    counts = tuple(int(a) for a in argv[1:]) or (4, 20, 50, 100)
    for n, path in write_worlds(out_dir, counts, floor_plan).items():
        print('%3d erratics: %s' % (n, os.path.normpath(path)))


if __name__ == '__main__':
    main()
