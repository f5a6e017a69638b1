"""Ray casts for every beam of every ranger at once: the simulator's hot path.

Static obstacles (the floor plan, plain models) live on the world grid. Each free cell holds
D, its Chebyshev (chessboard) distance to the nearest occupied cell: the square of cells
within D - 1 of it is free. A beam in the cell jumps straight to where it leaves that square
(for D = 1, the cell itself: an exact cell walk), so it never skips an occupied cell and stops
at the exact entry point of the first one: ranges are quantised to the grid as Stage's are
(Stage walks the same grid). Beams creeping along a wall (small D) walk many cells at once
instead (exact, batched), the more the fewer beams are left. Moving bodies (other robots) are
few and rectangular: they are hit analytically. All loops run over numpy arrays of the
still-travelling beams; the Python loop runs once per march step, not per beam.

Units: the field and the march work in cells; the public functions take and give metres.
"""


import numpy as np

try:  # scipy's chessboard distance transform; without it the march walks cell by cell
    from scipy.ndimage import distance_transform_cdt
except ImportError:  # pragma: no cover - tools/debian-packages.txt installs python3-scipy
    distance_transform_cdt = None

OCCUPIED = 0            # field code of an occupied cell; a free cell holds D >= 1
BLOCK = 2               # the far field's transform runs on 2 x 2-cell blocks
MAX_CODE = 255          # D is capped (uint8): jumps of at most 254 cells (5 m at 2 cm)
FINE_CAP = 64           # the full-resolution transform is exact up to this D ...
STRIPE_ROWS = 512       # ... computed in stripes of this many rows
NUDGE = 1e-6            # cells: pushes a point past the boundary it stepped onto
WALK_MIN = 4            # boundary crossings per axis in one batched walk, at least ...
WALK_MAX = 256          # ... and at most
WALK_BUDGET = 2048      # crossings per axis in one walk over all its beams: bounds its arrays
WALK_STEP = 0.25        # a beam walks when its jump is shorter than this many times K cells
# the row of each per-beam constant in StaticField.march's table
_PX, _PY, _DX, _DY, _IX, _IY, _OX, _OY, _SX, _SY, _TEND, _N = range(12)


def chebyshev_field(occupied, block=BLOCK, fine_cap=FINE_CAP, stripe_rows=STRIPE_ROWS):
    """uint8 codes: OCCUPIED (0) for an occupied cell, else D >= 1 such that every cell
    within Chebyshev distance D - 1 of it is free, capped at MAX_CODE.

    Two lower bounds of the cell's chessboard distance to the nearest occupied cell, the
    larger kept: the exact one up to `fine_cap`, from the transform of the full grid in row
    stripes with a margin of `fine_cap` rows (bounded temporary memory), and a coarse one on
    `block` x `block` blocks (a block is occupied when any of its cells is) for the far
    field: the blocks within Db - 1 of a cell's block are free and cover every cell within
    block * (Db - 1) of it.
    """
    rows, cols = occupied.shape
    out = np.full((rows, cols), MAX_CODE, np.uint8)
    if not occupied.any():
        return out
    if distance_transform_cdt is None:
        out[:] = 1
        out[occupied] = OCCUPIED
        return out
    br, bc = -(-rows // block), -(-cols // block)
    padded = np.zeros((br * block, bc * block), bool)
    padded[:rows, :cols] = occupied
    blocks = padded.reshape(br, block, bc, block).any(axis=(1, 3))
    del padded
    d = distance_transform_cdt(~blocks, metric='chessboard')
    del blocks
    d -= 1
    d *= block
    d += 1
    np.clip(d, 1, MAX_CODE, out=d)
    coarse = d.astype(np.uint8)
    del d
    for k in range(block):
        for j in range(block):
            part = out[k::block, j::block]
            part[:] = coarse[:part.shape[0], :part.shape[1]]
    del coarse
    free = ~occupied
    for r0 in range(0, rows, stripe_rows):
        r1 = min(rows, r0 + stripe_rows)
        a, b = max(0, r0 - fine_cap), min(rows, r1 + fine_cap)
        d = distance_transform_cdt(free[a:b], metric='chessboard')[r0 - a:r1 - a]
        np.minimum(d, fine_cap, out=d)
        np.maximum(out[r0:r1], d, out=out[r0:r1], casting='unsafe')
    out[occupied] = OCCUPIED
    return out


class StaticField:
    """The static obstacles of one height band, ready for ray casts and collision checks."""

    def __init__(self, occupied, spec):
        self.spec = spec
        self.occupied = occupied
        self.code = chebyshev_field(occupied)
        self._flat = self.code.ravel()
        # reach (cells) of the free square round a cell, by code: D - 1, none when occupied
        self._reach = np.maximum(np.arange(256, dtype=float) - 1.0, 0.0)

    def cells(self, x, y):
        """Flat cell indices of world points, -1 outside the grid."""
        s = self.spec
        cx = np.floor((np.asarray(x) - s.origin_x) / s.resolution).astype(np.int64)
        cy = np.floor((np.asarray(y) - s.origin_y) / s.resolution).astype(np.int64)
        inside = (cx >= 0) & (cx < s.cols) & (cy >= 0) & (cy < s.rows)
        return np.where(inside, cy * s.cols + cx, -1)

    def any_occupied(self, x, y):
        idx = self.cells(x, y)
        ok = idx >= 0
        return bool((self._flat[idx[ok]] == OCCUPIED).any())

    def clearance(self, x, y):
        """A lower bound (m) of the distance from the point to the nearest occupied cell."""
        idx = self.cells(np.array([x]), np.array([y]))[0]
        if idx < 0:
            return 0.0
        return float(self._reach[self._flat[idx]]) * self.spec.resolution

    def march(self, ox, oy, ang, max_range):
        """Casts beams from world points (ox, oy) at world angles `ang` (arrays) up to
        `max_range` (m, array or scalar). Returns (range_m, cell): the distance to the first
        occupied cell (inf on a miss) and that cell's flat index (-1 on a miss)."""
        ang = np.asarray(ang, float)
        return self.march_dir(ox, oy, np.cos(ang), np.sin(ang), max_range)

    def march_dir(self, ox, oy, dx, dy, max_range):
        """march() with the beams' unit directions (cos, sin) given."""
        s = self.spec
        res = s.resolution
        n = np.size(dx)
        rng = np.full(n, np.inf)
        cell = np.full(n, -1, np.int64)
        if n == 0:
            return rng, cell
        k = np.empty((_N, n))
        k[_PX] = (np.asarray(ox, float) - s.origin_x) / res
        k[_PY] = (np.asarray(oy, float) - s.origin_y) / res
        k[_DX] = dx
        k[_DY] = dy
        k[_TEND] = np.asarray(max_range, float) / res
        px, py, dx, dy = k[_PX], k[_PY], k[_DX], k[_DY]
        with np.errstate(divide='ignore', invalid='ignore'):
            k[_IX] = np.where(dx != 0, 1.0 / dx, np.inf)   # not -inf for dx = -0.0
            k[_IY] = np.where(dy != 0, 1.0 / dy, np.inf)
            inv_x, inv_y = k[_IX], k[_IY]
            # clip each beam to the grid's box (slab test) so the march never leaves it
            eps = 1e-3      # cells: keeps every point the march looks at inside the grid
            tx0 = np.where(dx != 0, (eps - px) * inv_x, -np.inf)
            tx1 = np.where(dx != 0, (s.cols - eps - px) * inv_x, np.inf)
            ty0 = np.where(dy != 0, (eps - py) * inv_y, -np.inf)
            ty1 = np.where(dy != 0, (s.rows - eps - py) * inv_y, np.inf)
        inside_x = (dx != 0) | ((px > 0) & (px < s.cols))
        inside_y = (dy != 0) | ((py > 0) & (py < s.rows))
        t = np.maximum(0.0, np.maximum(np.minimum(tx0, tx1), np.minimum(ty0, ty1)))
        np.minimum(k[_TEND], np.minimum(np.maximum(tx0, tx1), np.maximum(ty0, ty1)),
                   out=k[_TEND])
        live = np.flatnonzero(inside_x & inside_y & (t <= k[_TEND]))
        # the boundary ahead of a point in cell c is c + off; the free square's is that
        # plus sign * reach
        k[_OX] = dx >= 0
        k[_OY] = dy >= 0
        k[_SX] = 2.0 * k[_OX] - 1.0
        k[_SY] = 2.0 * k[_OY] - 1.0
        if live.size < n:
            k, t = k[:, live], t[live]
        flat, reach, cols = self._flat, self._reach, s.cols
        while live.size:
            px, py, dx, dy, inv_x, inv_y, offx, offy, sx, sy, tend = k[:_N]
            x = dx * t
            x += px
            y = dy * t
            y += py
            cx = np.floor(x)
            cy = np.floor(y)
            fi = cy * cols
            fi += cx
            idx = fi.astype(np.intp)
            code = flat[idx]
            hit = code == OCCUPIED
            if hit.any():
                rng[live[hit]] = t[hit] * res
                cell[live[hit]] = idx[hit]
            r = reach[code]
            # where the beam leaves the free square round its cell
            ex = sx * r
            ex += offx
            ex += cx
            ex -= x
            ex *= inv_x
            ey = sy * r
            ey += offy
            ey += cy
            ey -= y
            ey *= inv_y
            np.minimum(ex, ey, out=ex)
            ex += NUDGE
            t0 = t
            t = t + ex
            # beams with little room walk: a batched walk of K crossings per axis costs
            # about 2K jumps' worth of arithmetic but saves K / D Python iterations
            kw = min(WALK_MAX, max(WALK_MIN, WALK_BUDGET // live.size))
            walk = ex < WALK_STEP * kw
            walk &= ~hit
            walk = np.flatnonzero(walk)
            if walk.size:
                kw = min(WALK_MAX, max(WALK_MIN, WALK_BUDGET // walk.size))
                wt, whit, wcell = self._walk(k[:, walk], cx[walk], cy[walk], t0[walk], kw)
                t[walk] = wt
                if whit.any():
                    hw = walk[whit]
                    rng[live[hw]] = wt[whit] * res
                    cell[live[hw]] = wcell[whit]
                    hit[hw] = True
            keep = t < tend
            keep &= ~hit
            if not keep.all():
                live, t, k = live[keep], t[keep], k[:, keep]
        return rng, cell

    def _walk(self, k, cx, cy, tcur, kw):
        """An exact cell walk of kw x- and kw y-boundary crossings at once.

        The crossings of x = integer and y = integer lines are known in closed form; merged
        every crossing before the earlier of the two last ones is present, and the point
        just past each crossing lies in the cell entered there; the earliest occupied one is
        the hit. Returns the new t (the entry of the first occupied cell on a hit), the hit
        flags and the hit cells."""
        px, py, dx, dy, inv_x, inv_y, offx, offy, sx, sy, tend = (
            v[:, None] for v in k[:_N])
        steps = np.arange(kw, dtype=float)[None, :]
        tt = np.empty((len(cx), 2 * kw))
        tx, ty = tt[:, :kw], tt[:, kw:]
        np.multiply(steps, sx, out=tx)
        tx += (cx[:, None] + offx) - px
        tx *= inv_x
        np.multiply(steps, sy, out=ty)
        ty += (cy[:, None] + offy) - py
        ty *= inv_y
        lim = np.minimum(tx[:, -1], ty[:, -1])
        valid = tt <= lim[:, None]
        valid &= tt < tend
        # invalid crossings look at the current cell (always inside the grid: tend stops
        # short of the grid's edge)
        tn = np.where(valid, tt, tcur[:, None])
        tn += NUDGE
        qy = dy * tn
        qy += py
        qi = np.floor(qy, out=qy)
        qi *= self.spec.cols
        qx = np.multiply(dx, tn, out=tn)
        qx += px
        qi += np.floor(qx, out=qx)
        qi = qi.astype(np.intp)
        occ = self._flat[qi] == OCCUPIED
        occ &= valid
        # the first occupied cell entered is the one with the earliest entry time
        tt[~occ] = np.inf
        first = tt.argmin(axis=1)
        rows = np.arange(len(cx))
        tf = tt[rows, first]
        hit = tf < np.inf
        t = np.where(hit, tf, lim + NUDGE)
        return t, hit, qi[rows, first]


def ray_boxes(ox, oy, ang, boxes):
    """Distances (m) along beams to the nearest of some rotated rectangles, inf on a miss.

    `boxes`: K x 5 array (cx, cy, yaw, half_x, half_y). A beam starting inside a box reads 0.
    Vectorised over beams x boxes (slab test in each box's frame)."""
    n = np.size(ang)
    out = np.full(n, np.inf)
    if len(boxes) == 0 or n == 0:
        return out, np.full(n, -1)
    b = np.asarray(boxes, float)
    c, s = np.cos(b[:, 2])[None, :], np.sin(b[:, 2])[None, :]
    rx = (np.asarray(ox, float) * np.ones(n))[:, None] - b[None, :, 0]
    ry = (np.asarray(oy, float) * np.ones(n))[:, None] - b[None, :, 1]
    lx = c * rx + s * ry
    ly = -s * rx + c * ry
    da = np.asarray(ang)[:, None] - b[None, :, 2]
    dx, dy = np.cos(da), np.sin(da)
    hx, hy = b[None, :, 3], b[None, :, 4]
    with np.errstate(divide='ignore', invalid='ignore'):
        t1x, t2x = (-hx - lx) / dx, (hx - lx) / dx
        t1y, t2y = (-hy - ly) / dy, (hy - ly) / dy
        tnx = np.where(dx == 0, np.where(np.abs(lx) <= hx, -np.inf, np.inf), np.minimum(t1x, t2x))
        tfx = np.where(dx == 0, np.where(np.abs(lx) <= hx, np.inf, -np.inf), np.maximum(t1x, t2x))
        tny = np.where(dy == 0, np.where(np.abs(ly) <= hy, -np.inf, np.inf), np.minimum(t1y, t2y))
        tfy = np.where(dy == 0, np.where(np.abs(ly) <= hy, np.inf, -np.inf), np.maximum(t1y, t2y))
    tn = np.maximum(tnx, tny)
    tf = np.minimum(tfx, tfy)
    hit = (tn <= tf) & (tf >= 0)
    t = np.where(hit, np.maximum(tn, 0.0), np.inf)
    which = np.argmin(t, axis=1)
    out = t[np.arange(n), which]
    which = np.where(np.isfinite(out), which, -1)
    return out, which
