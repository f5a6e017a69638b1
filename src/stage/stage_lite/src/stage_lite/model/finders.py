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
from operator import attrgetter

import numpy as np

from .jit import kernel, njit, prange
from .motion import normalize
from .motion import pose_add as pose_add_kernel
from .raytrace import trace

#: From this many finder-candidate pairs in a step, the finders are shared among numba's
#: threads (each pair may cost a ray).
PARALLEL_CANDIDATES = 1000
_KEY = attrgetter('fiducial_key')          # read each step: a model's may change
_RETURN = attrgetter('fiducial_return')


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
    member_root, member_index, _, by_rank, rank_at = index.constants(members)
    at, fixed, tree = _finder_constants(index, finders, sight)
    # the members' and the finders' global poses, the finders' bodies' frames
    poses = index.poses(members, at=member_index)
    member_key = np.array(list(map(_KEY, members)), np.int64)
    member_return = np.array(list(map(_RETURN, members)), np.int64)
    fin = np.empty((n, 10), np.float64)
    fin[:, 0:3] = index.poses(finders, at=at)[:, (0, 1, 3)]
    fin[:, 3:7] = index.poses(finders, body=True, at=at)
    fin[:, 7:10] = fixed['floats']
    ints = np.empty((n, 3), np.int64)
    ints[:, 0] = list(map(_KEY, finders))
    ints[:, 1:3] = fixed['ints']
    # the static tables their rays read: one per (height, tree holding static bodies or not)
    z = fin[:, 5].tolist()
    classes = np.zeros(n, np.int64)
    if z.count(z[0]) == n and tree.count(tree[0]) == n:
        st = sight.static_first(z[0], tree[0])
    else:
        tables = []
        for i in range(n):
            got = sight.static_first(z[i], tree[i])
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
    see(fin, ints, classes, poses, index._order_x, index._order_y, by_rank, rank_at,
        member_key, member_root, member_index, member_return, layer, sp.ppm, sp.rx0,
        sp.ry0, sp.nrx, sp.nry, sp.reg_count, sp.reg_static, sp.reg_dyn, st, sp.dyn_head,
        sp.ent_block, sp.ent_next, sp.ent_seq, sp.blk_model, sp.blk_zmin, sp.blk_zmax,
        sight.model_root, sight.visible, count, nearest, *out)
    step = _Seen(members, poses, out, count, nearest)
    for i, f in enumerate(finders):     # (their readings are made from it when asked)
        f._seen = (step, i)


def _finder_constants(index, finders, sight):
    """(the finders' model indices, their 'ints' (root, ignore_zloc) and 'floats' (range_max,
    range_max_id, fov) of index.finder_table, the trees sight's static tables know them by,
    a list): what a finder does not change once loaded, kept per list of finders and
    sight (a run's updates take the same finders again and again)."""
    key = (tuple(finders), sight)
    cache = index.finder_sets
    got = cache.get(key)
    if got is None:
        if len(cache) > 64:
            cache.clear()
        rows = index.finder_rows(finders, sight)
        table = index.finder_table
        got = cache[key] = (table['ints'][rows, 3],
                            dict(ints=table['ints'][rows, 0:2],
                                 floats=table['floats'][rows]),
                            table['ints'][rows, 2].tolist())
    return got


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


@kernel
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
def _candidates(i, fin, xs, ys, order_x, order_y, by_rank, rank_at):
    """Finder i's candidates in Stage's order: the models in both sets' ranges (Stage's
    box, by the sets' bounds: nearby, _above), by rank. Marks instead of a set's
    intersection; ranked by a pass over every model when many are in the box, else by
    sorting their places in the ranking (the same order: ranks are distinct)."""
    m = xs.shape[0]
    gx, gy, rmax = fin[i, 0], fin[i, 1], fin[i, 7]
    sx = _bisect_right(xs, order_x, gx - rmax)
    ex = _bisect_right(xs, order_x, gx + rmax)
    sy = _bisect_right(ys, order_y, gy - rmax)
    ey = _bisect_right(ys, order_y, gy + rmax)
    mark = np.zeros(m, np.uint8)
    for k in range(sx, ex):
        mark[order_x[k]] = 1
    n = 0
    for k in range(sy, ey):
        c = order_y[k]
        if mark[c] == 1:
            mark[c] = 2
            n += 1
    cands = np.empty(n, np.int64)
    if 8 * n >= m:
        j = 0
        for k in range(m):
            c = by_rank[k]
            if mark[c] == 2:
                cands[j] = c
                j += 1
        return cands
    j = 0
    for k in range(sy, ey):
        c = order_y[k]
        if mark[c] == 2:
            cands[j] = rank_at[c]
            j += 1
    cands.sort()
    for k in range(n):
        cands[k] = by_rank[cands[k]]
    return cands


@njit(cache=True)
def _see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, by_rank, rank_at, key,
             root, index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
             st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
             model_root, visible, count, nearest, out_c, out_f, out_id):
    """Finder i's update (fin: gx, gy, ga, body x, y, z, a, range_max, range_max_id, fov;
    ints: key, root, ignore_zloc): its readings written to out from i * len(poses) on
    (candidate, range, bearing, his heading relative to the finder's, id), count[i] of
    them, and nearest[i] the range and heading of the first of the least range below 1e6
    (Fiducial.nearest), and 1 if there is one. The tests are Stage's, the cheap ones
    first (none has a side effect); a candidate surely out of range (its squared distance
    above range_max's by a relative 1e-9) or surely out of the field of view (its distance
    along the heading below range * (cos(fov / 2) - 1e-9): 1e-9 rad or more beyond it;
    the roundings are some 1e-16) is dropped before hypot and atan2."""
    m = poses.shape[0]
    gx, gy, ma = fin[i, 0], fin[i, 1], fin[i, 2]
    rmax = fin[i, 7]
    half = fin[i, 9] / 2.0
    far = rmax * rmax * (1.0 + 1e-9)
    cosma = math.cos(ma)
    sinma = math.sin(ma)
    behind = math.cos(half) - 1e-9 if half < math.pi else -2.0
    at = i * m
    for c in _candidates(i, fin, xs, ys, order_x, order_y, by_rank, rank_at):
        if ints[i, 0] != key[c] or root[c] == ints[i, 1]:
            continue
        dx = poses[c, 0] - gx
        dy = poses[c, 1] - gy
        if dx * dx + dy * dy > far:
            continue
        rng = math.hypot(dy, dx)
        if rng >= rmax or dx * cosma + dy * sinma < rng * behind:
            continue
        dtheta = normalize(math.atan2(dy, dx) - ma)
        if abs(dtheta) > half:
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
def _see_all(fin, ints, classes, poses, order_x, order_y, by_rank, rank_at, key, root, index,
             ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_first,
             dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
             model_root, visible, count, nearest, out_c, out_f, out_id):
    """Every finder's update (_see_one), in this thread."""
    xs = poses[:, 0].copy()
    ys = poses[:, 1].copy()
    for i in range(fin.shape[0]):
        _see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, by_rank, rank_at,
                 key, root, index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static,
                 reg_dyn, st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                 blk_zmax, model_root, visible, count, nearest, out_c, out_f, out_id)


@njit(parallel=True, cache=True)
def _see_all_parallel(fin, ints, classes, poses, order_x, order_y, by_rank, rank_at, key, root,
                      index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
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
        _see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, by_rank, rank_at,
                 key, root, index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static,
                 reg_dyn, st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                 blk_zmax, model_root, visible, count, nearest, out_c, out_f, out_id)
