"""Every due fiducial finder's update of a step in one numba kernel (no rospy).

The kernel (see_one per finder; sensing.update_all and sensing.sense run it, on numba's
threads beside the step's rays when there is enough work) does for each finder what
fiducial.Fiducial.update_one_by_one does, the same rule in the same order (fiducial.py's
docstring): the candidates from the index's sets (its bounds bisected as Python's bisect
does), key, range, field of view and tree, and a ray (raytrace.trace with sight.py's rule)
per candidate left; the readings' numbers are kept (_Seen) until a controller reads them
(Fiducial.fiducials makes them, Fiducial.nearest and fiducial.last_nearest_of read the
nearest without), each finder writing its own rows. What changes only with the finders'
sets is kept per set of finders (_FinderPlan).
"""
import math
from operator import attrgetter

import numpy as np

from .jit import kernel, njit
from .motion import normalize
from .motion import pose_add as pose_add_kernel
from .raytrace import trace

_KEY = attrgetter('fiducial_key')
_RETURN = attrgetter('fiducial_return')


def prepare_ids(ids, models, index, sight, layer):
    """ModelFiducial::Update of the finders `ids` (an int64 array of model indices, in update
    order; models(i) is the finder of index i) up to the kernel: a Finding, whose args
    (see_one's, for rows i) any thread may run, then publish(). Nothing moves between the
    finders' updates, so the poses are read once."""
    members = index._members
    if not members:
        return Finding([models(i) for i in ids.tolist()], None, None, sight.space, layer)
    # the kernel takes them in the order of their indices (each finder's update reads
    # nothing another writes): the same plan whatever order their worker queues gave
    ids = np.sort(ids)
    plan = _plan(ids, models, index, sight)
    n, m = len(plan.finders), len(members)
    member_root, member_index, _, by_rank, rank_at = index.constants(members)
    # the members' and the finders' global poses, the finders' bodies' frames: one call
    every = index.poses(plan.pose_models, body=plan.pose_body, at=plan.pose_at)
    poses = every[:m]
    fin = plan.fin
    fin[:, 0:3] = every[m:m + n][:, (0, 1, 3)]
    fin[:, 3:7] = every[m + n:]
    classes, st = plan.static_tables(sight, fin[:, 5])
    sp = sight.space
    count = np.zeros(n, np.int64)
    nearest = np.zeros((n, 3), np.float64)      # range, heading, whether any
    out = (np.empty(n * m, np.int64), np.empty((n * m, 3), np.float64),
           np.empty(n * m, np.int64))
    args = (fin, plan.ints, classes, poses, index._order_x, index._order_y, by_rank, rank_at,
            plan.member_key, member_root, member_index, plan.member_return, layer, sp.ppm,
            sp.rx0, sp.ry0, sp.nrx, sp.nry, sp.reg_count, sp.reg_static, sp.reg_dyn, st,
            sp.dyn_head, sp.ent_block, sp.ent_next, sp.ent_seq, sp.blk_model, sp.blk_zmin,
            sp.blk_zmax, sight.model_root, sight.visible, count, nearest, *out)
    step = _Seen(members, poses, out, count, nearest)
    if plan.any_nearest_only:       # what completing their readings takes, this step
        step.args = (fin.copy(),) + args[1:]        # (the plan's fin: the next update's)
        step.index, step.steps = index, index.steps
    return Finding(plan.finders, args, step, sight.space, layer)


class Finding:
    """A step's finder updates made ready (prepare_ids): the finders, the kernel's args
    (None: no fiducial-bearing model, nothing to see), the _Seen they fill, the space their
    rays walk and the grid layer they read."""

    __slots__ = ('finders', 'args', 'seen', 'space', 'layer')

    def __init__(self, finders, args, seen, space, layer):
        self.finders = finders
        self.args = args
        self.seen = seen
        self.space = space
        self.layer = layer

    def pairs(self):
        """The finder-candidate pairs (the work: each may cost a ray)."""
        return 0 if self.args is None else len(self.finders) * len(self.seen.members)

    def run(self):
        """The kernel, every finder in this thread."""
        if self.args is not None:
            _see_rows(np.arange(len(self.finders), dtype=np.int64), *self.args)

    def publish(self):
        """Each finder's readings, those the kernel found (made when asked)."""
        if self.args is None:
            for f in self.finders:
                f.fiducials = []
            return
        step = self.seen
        for i, f in enumerate(self.finders):
            f._seen = (step, i)


def _plan(ids, models, index, sight):
    """The _FinderPlan of the finders `ids` with index's members now, kept per list of
    finders (a run's updates take the same finders again and again)."""
    key = (ids.tobytes(), sight)
    cache = index.finder_sets
    plan = cache.get(key)
    if plan is None or plan.version != index.version:
        if len(cache) > 64:
            cache.clear()
        finders = [models(i) for i in ids.tolist()]
        plan = cache[key] = _FinderPlan(finders, index, sight)
    return plan


class _FinderPlan:
    """What the updates of a list of finders read that changes only with the finders' sets
    (index.version): the finders; the table of their constants (fin: gx, gy, ga, body x,
    y, z, a, range_max, range_max_id, fov, the poses filled in at each update; ints: key,
    root, ignore_zloc); the members' keys and returns; the one call of index.poses for the
    members' and the finders' global poses and the finders' bodies' frames; the static
    tables of their rays."""

    def __init__(self, finders, index, sight):
        self.version = index.version
        self.finders = finders
        rows = index.finder_rows(finders, sight)
        table = index.finder_table
        at = table['ints'][rows, 3]
        n = len(finders)
        self.fin = np.empty((n, 10), np.float64)
        self.fin[:, 7:10] = table['floats'][rows]
        self.ints = np.empty((n, 4), np.int64)
        self.ints[:, 0] = list(map(_KEY, finders))
        self.ints[:, 1:3] = table['ints'][rows, 0:2]
        self.ints[:, 3] = [index.nearest_only_allowed and f.nearest_only for f in finders]
        self.tree = table['ints'][rows, 2].tolist()
        self.any_nearest_only = bool(self.ints[:, 3].any())
        members = index._members
        _, member_index, _, _, _ = index.constants(members)
        self.member_key = np.array(list(map(_KEY, members)), np.int64)
        self.member_return = np.array(list(map(_RETURN, members)), np.int64)
        self.pose_models = list(members) + finders + finders
        self.pose_at = np.concatenate((member_index, at, at))
        self.pose_body = np.zeros(len(self.pose_at), np.bool_)
        self.pose_body[len(members) + n:] = True
        self._z = None
        self._tables = None

    def static_tables(self, sight, z):
        """(each finder's class, the static tables of the classes) for the finders' bodies'
        heights z: one table per (height, tree holding static bodies or not)."""
        if self._z is not None and np.array_equal(z, self._z):
            return self._tables
        n = len(self.finders)
        zs = z.tolist()
        tree = self.tree
        classes = np.zeros(n, np.int64)
        if zs.count(zs[0]) == n and tree.count(tree[0]) == n:
            st = sight.static_first(zs[0], tree[0])
        else:
            tables = []
            for i in range(n):
                got = sight.static_first(zs[i], tree[i])
                for k, t in enumerate(tables):
                    if t is got:
                        classes[i] = k
                        break
                else:
                    classes[i] = len(tables)
                    tables.append(got)
            st = np.concatenate(tables)
        self._z = z.copy()
        self._tables = (classes, st)
        return self._tables


class _Seen:
    """What the finders' kernel found: the members, their poses, the readings' numbers (each
    finder's from i * len(members) on, count[i] of them), each finder's nearest. A finder
    that reads its nearest only (count[i] -1) has its readings completed when asked, in the
    same step (complete)."""

    __slots__ = ('members', 'poses', 'out', 'count', 'nearest', 'args', 'index', 'steps')

    def __init__(self, members, poses, out, count, nearest):
        self.members = members
        self.poses = poses
        self.out = out
        self.count = count
        self.nearest = nearest
        self.args = self.index = self.steps = None

    def complete(self, i):
        """Finder i's readings as its update would have made them all: its rays again
        through the same grid layer from the same poses, which stay until the index's next
        step (begin_step; the moves then draw into that layer). RuntimeError once the world
        has stepped on."""
        if self.index.steps != self.steps:
            raise RuntimeError(
                'a fiducial finder that reads only its nearest (a controller said so) was '
                'asked for all its readings a step later: ask in the step of its update')
        ints = self.args[1].copy()
        ints[i, 3] = 0
        self.nearest[i] = 0.0
        _see_rows(np.array([i], np.int64), self.args[0], ints, *self.args[2:])


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
def see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, by_rank, rank_at, key,
            root, index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
            st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
            model_root, visible, count, nearest, out_c, out_f, out_id):
    """Finder i's update (fin: gx, gy, ga, body x, y, z, a, range_max, range_max_id, fov;
    ints: key, root, ignore_zloc, nearest only: if 1, nearest[i] alone (_see_nearest) and
    count[i] -1): its readings written to out from i * len(poses) on
    (candidate, range, bearing, his heading relative to the finder's, id), count[i] of
    them, and nearest[i] the range and heading of the first of the least range below 1e6
    (Fiducial.nearest), and 1 if there is one. The tests are Stage's, the cheap ones
    first (none has a side effect); a candidate surely out of range (its squared distance
    above range_max's by a relative 1e-9) or surely out of the field of view (its distance
    along the heading below range * (cos(fov / 2) - 1e-9): 1e-9 rad or more beyond it;
    the roundings are some 1e-16) is dropped before hypot and atan2."""
    m = poses.shape[0]
    ma = fin[i, 2]
    cands = _candidates(i, fin, xs, ys, order_x, order_y, by_rank, rank_at)
    if ints[i, 3] != 0:
        _see_nearest(i, cands, fin, ints, classes, poses, key, root, index, layer, ppm, rx0,
                     ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_first, dyn_head,
                     ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax, model_root,
                     visible, nearest)
        count[i] = -1
        return
    far, cosma, sinma, behind = _view_bounds(i, fin)
    at = i * m
    for c in cands:
        seen, rng, dtheta = _in_view(i, c, fin, ints, key, root, poses, far, cosma, sinma,
                                     behind, np.inf)
        if not seen or not _ray_reaches(
                i, c, dtheta, fin, ints, classes, index, layer, ppm, rx0, ry0, nrx, nry,
                reg_count, reg_static, reg_dyn, st_first, dyn_head, ent_block, ent_next,
                ent_seq, blk_model, blk_zmin, blk_zmax, model_root, visible):
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
def _see_nearest(i, cands, fin, ints, classes, poses, key, root, index, layer, ppm, rx0, ry0,
                 nrx, nry, reg_count, reg_static, reg_dyn, st_first, dyn_head, ent_block,
                 ent_next, ent_seq, blk_model, blk_zmin, blk_zmax, model_root, visible,
                 nearest):
    """Finder i's nearest[i] alone, as see_one finds it (the first of the least range of
    the candidates it sees), its readings not made: of the candidates that pass the rule's
    tests, the nearest not yet tried (ties in Stage's order), its ray cast, until one
    reaches its candidate. The rays to the others change nothing anyone reads."""
    far, cosma, sinma, behind = _view_bounds(i, fin)
    last_rng = -1.0         # the last tried: (its range, its place among the candidates)
    last_at = -1
    while True:
        best_rng = math.inf
        best_at = -1
        best_turn = 0.0
        for at in range(cands.shape[0]):
            seen, rng, dtheta = _in_view(i, cands[at], fin, ints, key, root, poses, far, cosma,
                                         sinma, behind, best_rng)
            if seen and (rng > last_rng or (rng == last_rng and at > last_at)):
                best_rng = rng          # the first of the least range not tried yet
                best_at = at
                best_turn = dtheta
        if best_at < 0 or best_rng >= 1e6:
            return
        c = cands[best_at]
        if _ray_reaches(i, c, best_turn, fin, ints, classes, index, layer, ppm, rx0, ry0,
                        nrx, nry, reg_count, reg_static, reg_dyn, st_first, dyn_head,
                        ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
                        model_root, visible):
            nearest[i, 0] = best_rng
            nearest[i, 1] = normalize(poses[c, 3] - fin[i, 2])
            nearest[i, 2] = 1.0
            return
        last_rng = best_rng
        last_at = best_at


@kernel
def _view_bounds(i, fin):
    """Finder i's bounds of the cheap tests (_in_view): range_max squared by a relative
    1e-9, its heading's cosine and sine, and cos(fov / 2) less 1e-9 (-2 for a whole
    circle)."""
    rmax = fin[i, 7]
    half = fin[i, 9] / 2.0
    return (rmax * rmax * (1.0 + 1e-9), math.cos(fin[i, 2]), math.sin(fin[i, 2]),
            math.cos(half) - 1e-9 if half < math.pi else -2.0)


@kernel
def _in_view(i, c, fin, ints, key, root, poses, far, cosma, sinma, behind, below):
    """(whether finder i's rule keeps candidate c before the ray: key, tree, range, field of
    view; its range, its bearing), the cheap tests first (see_one's docstring); a range
    of `below` or more is not kept (nor its bearing computed)."""
    if ints[i, 0] != key[c] or root[c] == ints[i, 1]:
        return False, 0.0, 0.0
    dx = poses[c, 0] - fin[i, 0]
    dy = poses[c, 1] - fin[i, 1]
    if dx * dx + dy * dy > far:
        return False, 0.0, 0.0
    rng = math.hypot(dy, dx)
    if rng >= fin[i, 7] or rng >= below or dx * cosma + dy * sinma < rng * behind:
        return False, rng, 0.0
    dtheta = normalize(math.atan2(dy, dx) - fin[i, 2])
    return abs(dtheta) <= fin[i, 9] / 2.0, rng, dtheta


@kernel
def _ray_reaches(i, c, dtheta, fin, ints, classes, index, layer, ppm, rx0, ry0, nrx, nry,
                 reg_count, reg_static, reg_dyn, st_first, dyn_head, ent_block, ent_next,
                 ent_seq, blk_model, blk_zmin, blk_zmax, model_root, visible):
    """Whether finder i's ray at bearing dtheta (from its body's frame, range_max long)
    stops at candidate c first (with ignore_zloc, or at nothing)."""
    ox, oy, oz, oa = pose_add_kernel(fin[i, 3], fin[i, 4], fin[i, 5], fin[i, 6], 0.0, 0.0,
                                     0.0, dtheta)
    _, hit = trace(ox, oy, oz, oa, fin[i, 7], ppm, classes[i], ints[i, 1], layer, rx0, ry0,
                   nrx, nry, reg_count, reg_static, reg_dyn, st_first, dyn_head, ent_block,
                   ent_next, ent_seq, blk_model, blk_zmin, blk_zmax, model_root, visible)
    if ints[i, 2] != 0 and hit < 0:
        hit = index[c]
    return hit == index[c]


@njit(cache=True)
def _see_rows(rows, fin, ints, classes, poses, order_x, order_y, by_rank, rank_at, key, root,
              index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
              st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
              model_root, visible, count, nearest, out_c, out_f, out_id):
    """The updates of the finders `rows` (see_one), in this thread."""
    xs = poses[:, 0].copy()
    ys = poses[:, 1].copy()
    for i in rows:
        see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, by_rank, rank_at,
                key, root, index, ret, layer, ppm, rx0, ry0, nrx, nry, reg_count, reg_static,
                reg_dyn, st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                blk_zmax, model_root, visible, count, nearest, out_c, out_f, out_id)
