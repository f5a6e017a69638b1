"""Ray casts for every beam of every ranger at once: the simulator's hot path.

Static obstacles (the floor plan, plain models) live on the world grid. A beam is marched
through it by sphere tracing on a precomputed distance field: from a point in cell c it may
jump by a lower bound of the distance from anywhere in c to the nearest occupied cell, or at
least to where it leaves c (an exact cell walk near walls). It stops at the exact entry point of
the first occupied cell, so ranges are quantised to the grid as Stage's are (Stage walks the
same grid). Moving bodies (other robots) are few and rectangular: they are hit analytically.
All loops run over numpy arrays of the still-travelling beams; the Python loop runs once per
march step, not per beam.

Units: the field and the march work in cells; the public functions take and give metres.
"""

import math

import numpy as np

try:  # scipy's exact Euclidean distance transform; without it the march walks cell by cell
    from scipy.ndimage import distance_transform_edt
except ImportError:  # pragma: no cover - the workspace installs python3-scipy
    distance_transform_edt = None

OCCUPIED = 255          # field code of an occupied cell
BLOCK = 2               # the distance transform runs on 2 x 2-cell blocks: a quarter of the
                        # time and memory, for jumps at most ~3 cells shorter near walls
SAFE_CAP = 64           # blocks: field codes are capped at 2 * 64 = 128 cells (2.56 m at 2 cm);
                        # bounds the transform's stripe margin and so its temporary memory
STRIPE_ROWS = 192       # block rows per distance-transform stripe
NUDGE = 1e-6            # cells: pushes a point past the boundary it stepped onto
SQRT2 = math.sqrt(2.0)
WALK_CELLS = 4          # crossings per axis in one batched cell walk
_WALK_K = np.arange(WALK_CELLS, dtype=float)


def safe_field(occupied, block=BLOCK, cap=SAFE_CAP):
    """uint8 codes: OCCUPIED for an occupied cell, else floor of a lower bound (cells) of the
    distance from any point of the cell to any occupied cell, at most block * cap.

    On `block` x `block` blocks (a block is occupied when any of its cells is), the Euclidean
    transform gives the centre-to-centre distance d; two unit squares whose centres are d
    apart are at least d - sqrt(2) apart, and every cell lies inside its block. Computed in
    row stripes with a margin of `cap` rows: exact up to `cap`, a lower bound above.
    """
    rows, cols = occupied.shape
    out = np.zeros((rows, cols), np.uint8)
    if not occupied.any():
        out[:] = min(254, block * cap)
        return out
    if distance_transform_edt is None:
        out[occupied] = OCCUPIED
        return out
    br, bc = -(-rows // block), -(-cols // block)
    padded = np.zeros((br * block, bc * block), bool)
    padded[:rows, :cols] = occupied
    blocks = padded.reshape(br, block, bc, block).any(axis=(1, 3))
    del padded
    coarse = np.zeros((br, bc), np.uint8)
    margin = cap + 2
    for r0 in range(0, br, STRIPE_ROWS):
        r1 = min(br, r0 + STRIPE_ROWS)
        a, b = max(0, r0 - margin), min(br, r1 + margin)
        d = distance_transform_edt(~blocks[a:b])[r0 - a:r1 - a]
        d -= SQRT2
        np.clip(d, 0, cap, out=d)
        d *= block
        np.minimum(d, 254, out=d)
        coarse[r0:r1] = d.astype(np.uint8)
    for k in range(block):
        for j in range(block):
            part = out[k::block, j::block]
            part[:] = coarse[:part.shape[0], :part.shape[1]]
    out[occupied] = OCCUPIED
    return out


class StaticField:
    """The static obstacles of one height band, ready for ray casts and collision checks."""

    def __init__(self, occupied, spec):
        self.spec = spec
        self.occupied = occupied
        self.code = safe_field(occupied)
        self._flat = self.code.ravel()

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
        v = int(self._flat[idx])
        return 0.0 if v == OCCUPIED else v * self.spec.resolution

    def march(self, ox, oy, ang, max_range):
        """Casts beams from world points (ox, oy) at world angles `ang` (arrays) up to
        `max_range` (m, array or scalar). Returns (range_m, cell): the distance to the first
        occupied cell (inf on a miss) and that cell's flat index (-1 on a miss)."""
        s = self.spec
        res = s.resolution
        n = np.size(ang)
        rng = np.full(n, np.inf)
        cell = np.full(n, -1, np.int64)
        if n == 0:
            return rng, cell
        dx = np.cos(ang)
        dy = np.sin(ang)
        px = (np.asarray(ox, float) - s.origin_x) / res * np.ones(n)
        py = (np.asarray(oy, float) - s.origin_y) / res * np.ones(n)
        tend = np.broadcast_to(np.asarray(max_range, float) / res, (n,)).copy()
        with np.errstate(divide='ignore', invalid='ignore'):
            inv_x = np.where(dx != 0, 1.0 / dx, np.inf)
            inv_y = np.where(dy != 0, 1.0 / dy, np.inf)
            # clip each beam to the grid's box (slab test) so the march never leaves it
            eps = 1e-3      # cells: keeps every point the march looks at inside the grid
            tx0 = np.where(dx != 0, (eps - px) * inv_x, -np.inf)
            tx1 = np.where(dx != 0, (s.cols - eps - px) * inv_x, np.inf)
            ty0 = np.where(dy != 0, (eps - py) * inv_y, -np.inf)
            ty1 = np.where(dy != 0, (s.rows - eps - py) * inv_y, np.inf)
        inside_x = (dx != 0) | ((px > 0) & (px < s.cols))
        inside_y = (dy != 0) | ((py > 0) & (py < s.rows))
        t = np.maximum(0.0, np.maximum(np.minimum(tx0, tx1), np.minimum(ty0, ty1)))
        tend = np.minimum(tend, np.minimum(np.maximum(tx0, tx1), np.maximum(ty0, ty1)))
        live = np.flatnonzero(inside_x & inside_y & (t <= tend))
        # per-beam constants of the cell walk: the boundary ahead is cell + off
        offx = (dx >= 0).astype(float)
        offy = (dy >= 0).astype(float)
        px, py, dx, dy = px[live], py[live], dx[live], dy[live]
        inv_x, inv_y, offx, offy = inv_x[live], inv_y[live], offx[live], offy[live]
        t, tend = t[live], tend[live]
        flat = self._flat
        cols = s.cols
        while live.size:
            x = px + dx * t
            y = py + dy * t
            cx = np.floor(x)
            cy = np.floor(y)
            idx = cy.astype(np.int64) * cols + cx.astype(np.int64)
            code = flat[idx]
            hit = code == OCCUPIED
            if hit.any():
                rng[live[hit]] = t[hit] * res
                cell[live[hit]] = idx[hit]
            step = np.minimum((cx + offx - x) * inv_x, (cy + offy - y) * inv_y)
            np.maximum(step, code, out=step)
            t0 = t
            t = t + step + NUDGE
            walk = np.flatnonzero(code < WALK_CELLS)
            if walk.size:
                # near a wall jumps shrink (sphere tracing crawls along a wall at a
                # shallow angle): walk at least WALK_CELLS cells exactly instead
                wt, whit, wcell = self._walk(px[walk], py[walk], dx[walk], dy[walk],
                                             inv_x[walk], inv_y[walk], cx[walk], cy[walk],
                                             t0[walk], tend[walk])
                t[walk] = wt
                if whit.any():
                    hw = walk[whit]
                    rng[live[hw]] = wt[whit] * res
                    cell[live[hw]] = wcell[whit]
                    hit[hw] = True
            keep = ~hit & (t < tend)
            if not keep.all():
                live, t, tend = live[keep], t[keep], tend[keep]
                px, py, dx, dy = px[keep], py[keep], dx[keep], dy[keep]
                inv_x, inv_y, offx, offy = inv_x[keep], inv_y[keep], offx[keep], offy[keep]
        return rng, cell


    def _walk(self, px, py, dx, dy, inv_x, inv_y, cx, cy, tcur, tend):
        """An exact cell walk of WALK_CELLS x- and WALK_CELLS y-boundary crossings at once.

        The crossings of x = integer and y = integer lines are known in closed form; merged
        every crossing before the earlier of the two last ones is present, and the point
        just past each crossing lies in the cell entered there; the earliest occupied one is
        the hit. Returns the new
        t (the entry of the first occupied cell on a hit), the hit flags and the hit cells."""
        s = self.spec
        k = _WALK_K[None, :]
        sx = np.where(dx >= 0, 1.0, -1.0)[:, None]
        sy = np.where(dy >= 0, 1.0, -1.0)[:, None]
        bx = (cx + (dx >= 0))[:, None] + k * sx
        by = (cy + (dy >= 0))[:, None] + k * sy
        tx = (bx - px[:, None]) * inv_x[:, None]
        ty = (by - py[:, None]) * inv_y[:, None]
        lim = np.minimum(tx[:, -1], ty[:, -1])
        tt = np.concatenate((tx, ty), axis=1)
        valid = (tt <= lim[:, None]) & (tt < tend[:, None])
        # invalid crossings look at the current cell (always inside the grid: tend stops
        # short of the grid's edge)
        tn = np.where(valid, tt, tcur[:, None]) + NUDGE
        qi = (np.floor(py[:, None] + dy[:, None] * tn).astype(np.int64) * s.cols
              + np.floor(px[:, None] + dx[:, None] * tn).astype(np.int64))
        occ = (self._flat[qi] == OCCUPIED) & valid
        # the first occupied cell entered is the one with the earliest entry time
        first = np.where(occ, tt, np.inf).argmin(axis=1)
        rows = np.arange(len(px))
        hit = occ[rows, first]
        t = np.where(hit, tt[rows, first], lim + NUDGE)
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
