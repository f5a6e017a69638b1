"""Writes Stage worlds of N erratics (the lesson's robot and 1081-beam laser) on the office plan.

Run: `/usr/bin/python3 bench/make_stage_worlds.py [OUT_DIR] [N ...]` with the devel space
sourced (or PYTHONPATH=src/stage/stage_lite/src); defaults: OUT_DIR build/stage_worlds,
N = 20 50 100. Prints the paths written.

The worlds copy the lesson's (src/stage_multi/world/willow-multi-erratic.world: resolution,
interval_sim, the floor plan with its size and pose, the erratic and topurg definitions) and
stand the robots on free floor at least 1.2 m from every wall and from each other, chosen
deterministically (a fixed-seed shuffle of the free places), each with a fixed-seed yaw. The
floor plan is named by absolute path, so the worlds load from any folder.
"""

import math
import os
import sys

import numpy as np
from scipy.ndimage import distance_transform_edt
from stage_lite.world import load_world

HERE = os.path.dirname(os.path.abspath(__file__))
WORLD_DIR = os.path.join(HERE, '..', 'src', 'stage_multi', 'world')
LESSON = os.path.join(WORLD_DIR, 'willow-multi-erratic.world')
CLEARANCE_M = 1.2       # from walls and between robot centres (the figure)
CELL_M = 0.1            # candidate places on a 10 cm lattice
SEED = 20140            # fixed: the same worlds on every machine
COLORS = ('blue', 'red', 'green', 'magenta', 'cyan', 'orange', 'purple', 'yellow', 'brown',
          'black')


def free_places(count, seed=SEED):
    """`count` (x, y, yaw) on the lesson's floor plan, >= CLEARANCE_M from walls and apart."""
    w = load_world(LESSON)
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


def world_text(places):
    with open(LESSON) as f:
        lesson = f.read()
    head = lesson[:lesson.index('# throw in a robot')]
    head = head.replace('bitmap "office.pgm"', 'bitmap "%s"'
                        % os.path.abspath(os.path.join(WORLD_DIR, 'office.pgm')))
    lines = [head, '# %d erratics (bench/make_stage_worlds.py)\n' % len(places)]
    for i, (x, y, yaw) in enumerate(places):
        lines.append('erratic( pose [ %.2f %.2f 0 %.1f ] name "robot%d" color "%s")\n'
                     % (x, y, yaw, i, COLORS[i % len(COLORS)]))
    return ''.join(lines)


def write_worlds(out_dir, counts=(20, 50, 100)):
    """Writes erratics_<N>.world for each N; returns {N: path}."""
    os.makedirs(out_dir, exist_ok=True)
    places = free_places(max(counts))
    out = {}
    for n in counts:
        path = os.path.join(out_dir, 'erratics_%d.world' % n)
        with open(path, 'w') as f:
            f.write(world_text(places[:n]))
        out[n] = path
    return out


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    out_dir = argv[0] if argv else os.path.join(HERE, '..', 'build', 'stage_worlds')
    counts = tuple(int(a) for a in argv[1:]) or (20, 50, 100)
    for n, path in write_worlds(out_dir, counts).items():
        print('%3d erratics: %s' % (n, os.path.normpath(path)))


if __name__ == '__main__':
    main()
