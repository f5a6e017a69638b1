"""Every due fiducial finder's update of a step in one numba kernel (no rospy).

update_all does for each finder what fiducial.Fiducial.update_one_by_one does, the same
rule in the same order (fiducial.py's docstring): the candidates from the index's sets (its
bounds bisected as Python's bisect does), key, range, field of view and tree, and a ray
(raytrace.trace with sight.py's rule) per candidate left; the readings' numbers are kept
(_Seen) until a controller reads them (Fiducial.fiducials makes them, Fiducial.nearest and
last_nearest read the nearest without). From PARALLEL_CANDIDATES finder-candidate pairs
the finders are shared among numba's threads, each writing its own rows.
"""
import math

import numpy as np

from .jit import njit, prange
from .motion import normalize
from .motion import pose_add as pose_add_kernel
from .raytrace import trace

#: From this many finder-candidate pairs in a step, the finders are shared among numba's
#: threads (each pair may cost a ray).
PARALLEL_CANDIDATES = 1000


def update_all(finders, index, sight, layer):
    """ModelFiducial::Update of each finder in turn, as Fiducial.update_one_by_one does it,
    in one kernel: the candidates (index's sets, their global poses now), the rule and the
    rays (sight's). Nothing moves between the finders' updates, so the poses are read once."""
    members = index._members
    if not members:
        for f in finders:
            f.fiducials = []
        return
    n, m = len(finders), len(members)
    member_root, member_index, _ = index.constants(members)
    poses = index.poses(members, at=member_index)
    member_key = np.fromiter((h.fiducial_key for h in members), np.int64, m)
    member_return = np.fromiter((h.fiducial_return for h in members), np.int64, m)
    rows = index.finder_rows(finders, sight)
    table = index.finder_table
    fin = np.empty((n, 10), np.float64)
    at = table['ints'][rows, 3]
    fin[:, 0:3] = index.poses(finders, at=at)[:, (0, 1, 3)]
    fin[:, 3:7] = index.poses(finders, body=True, at=at)
    fin[:, 7:10] = table['floats'][rows]
    ints = np.empty((n, 3), np.int64)
    ints[:, 0] = np.fromiter((f.fiducial_key for f in finders), np.int64, n)
    ints[:, 1:3] = table['ints'][rows, 0:2]
    # the static tables their rays read: one per (height, tree holding static bodies or not)
    z, tree = fin[:, 5], table['ints'][rows, 2]
    classes = np.zeros(n, np.int64)
    if (z == z[0]).all() and (tree == tree[0]).all():
        st = sight.static_first(float(z[0]), int(tree[0]))
    else:
        tables = []
        for i in range(n):
            got = sight.static_first(float(z[i]), int(tree[i]))
            for k, t in enumerate(tables):
                if t is got:
                    classes[i] = k
                    break
            else:
                classes[i] = len(tables)
                tables.append(got)
        st = np.concatenate(tables)
    sp = sight.space
    count = np.zeros(n, np.int64)
    nearest = np.zeros((n, 3), np.float64)      # range, heading, whether any
    out = (np.empty(n * m, np.int64), np.empty((n * m, 3), np.float64),
           np.empty(n * m, np.int64))
    see = _see_all_parallel if n * m >= PARALLEL_CANDIDATES else _see_all
    see(fin, ints, classes, poses, index._order_x, index._order_y, index._ranks, member_key,
        member_root, member_index, member_return, layer, sp.ppm, sp.rx0, sp.ry0, sp.nrx,
        sp.nry, sp.reg_count, sp.reg_static, sp.reg_dyn, st, sp.dyn_head, sp.ent_block,
        sp.ent_next, sp.ent_seq, sp.blk_model, sp.blk_zmin, sp.blk_zmax, sight.model_root,
        sight.visible, count, nearest, *out)
    step = _Seen(members, poses, out, count, nearest)
    for i, f in enumerate(finders):
        f._fiducials = []
        f._seen = (step, i)


class _Seen:
    """What update_all's kernel found: the members, their poses, the readings' numbers (each
    finder's from i * len(members) on, count[i] of them), each finder's nearest."""

    __slots__ = ('members', 'poses', 'out', 'count', 'nearest')

    def __init__(self, members, poses, out, count, nearest):
        self.members = members
        self.poses = poses
        self.out = out
        self.count = count
        self.nearest = nearest


@njit(cache=True)
def _bisect_right(keys, order, x):
    """bisect.bisect_right over keys[order[...]] (sorted or not, as Python's does it)."""
    lo = 0
    hi = order.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if x < keys[order[mid]]:
            hi = mid
        else:
            lo = mid + 1
    return lo


@njit(cache=True)
def _see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, ranks, key, root, index,
             ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_first,
             dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
             model_root, visible, count, nearest, out_c, out_f, out_id):
    """Finder i's update (fin: gx, gy, ga, body x, y, z, a, range_max, range_max_id, fov;
    ints: key, root, ignore_zloc): its readings written to out from i * len(poses) on
    (candidate, range, bearing, his heading relative to the finder's, id), count[i] of
    them, and nearest[i] the range and heading of the first of the least range below 1e6
    (Fiducial.nearest), and 1 if there is one."""
    m = poses.shape[0]
    gx, gy, ma = fin[i, 0], fin[i, 1], fin[i, 2]
    rmax = fin[i, 7]
    # the candidates: Stage's box, by the sets' bounds (nearby, _above)
    sx = _bisect_right(xs, order_x, gx - rmax)
    ex = _bisect_right(xs, order_x, gx + rmax)
    sy = _bisect_right(ys, order_y, gy - rmax)
    ey = _bisect_right(ys, order_y, gy + rmax)
    in_x = np.zeros(m, np.bool_)
    for k in range(sx, ex):
        in_x[order_x[k]] = True
    picked = np.empty(m, np.int64)
    n = 0
    for k in range(sy, ey):
        c = order_y[k]
        if in_x[c]:
            in_x[c] = False         # a model is in a set once
            picked[n] = c
            n += 1
    cands = picked[:n][np.argsort(ranks[picked[:n]], kind='mergesort')]
    at = i * m
    for c in cands:
        if ints[i, 0] != key[c]:
            continue
        dx = poses[c, 0] - gx
        dy = poses[c, 1] - gy
        rng = math.hypot(dy, dx)
        if rng >= rmax:
            continue
        dtheta = normalize(math.atan2(dy, dx) - ma)
        if abs(dtheta) > fin[i, 9] / 2.0:
            continue
        if root[c] == ints[i, 1]:
            continue
        ox, oy, oz, oa = pose_add_kernel(fin[i, 3], fin[i, 4], fin[i, 5], fin[i, 6], 0.0,
                                         0.0, 0.0, dtheta)
        _, hit = trace(ox, oy, oz, oa, rmax, ppm, classes[i], ints[i, 1], layer, rx0, ry0,
                       nrx, nry, reg_count, reg_static, reg_dyn, st_first, dyn_head,
                       ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
                       model_root, visible)
        if ints[i, 2] != 0 and hit < 0:
            hit = index[c]
        if hit != index[c]:
            continue
        out_c[at] = c
        out_f[at, 0] = rng
        out_f[at, 1] = dtheta
        out_f[at, 2] = normalize(poses[c, 3] - ma)
        out_id[at] = ret[c] if rng < fin[i, 8] else 0
        if rng < (nearest[i, 0] if nearest[i, 2] != 0.0 else 1e6):
            nearest[i, 0] = rng
            nearest[i, 1] = out_f[at, 2]
            nearest[i, 2] = 1.0
        at += 1
    count[i] = at - i * m


@njit(cache=True)
def _see_all(fin, ints, classes, poses, order_x, order_y, ranks, key, root, index, ret,
             layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_first,
             dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
             model_root, visible, count, nearest, out_c, out_f, out_id):
    """Every finder's update (_see_one), in this thread."""
    xs = poses[:, 0].copy()
    ys = poses[:, 1].copy()
    for i in range(fin.shape[0]):
        _see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, ranks, key, root,
                 index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
                 st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                 blk_zmax, model_root, visible, count, nearest, out_c, out_f, out_id)


@njit(parallel=True, cache=True)
def _see_all_parallel(fin, ints, classes, poses, order_x, order_y, ranks, key, root, index,
                      ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
                      st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                      blk_zmax, model_root, visible, count, nearest, out_c, out_f, out_id):
    """_see_all, the finders shared among numba's threads (each writes its own rows),
    dealt out in turn (neighbouring finders, whose work is alike, to different threads)."""
    xs = poses[:, 0].copy()
    ys = poses[:, 1].copy()
    n = fin.shape[0]
    half = (n + 1) // 2
    for j in prange(n):
        i = 2 * j if j < half else 2 * (j - half) + 1
        _see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, ranks, key, root,
                 index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
                 st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                 blk_zmax, model_root, visible, count, nearest, out_c, out_f, out_id)
