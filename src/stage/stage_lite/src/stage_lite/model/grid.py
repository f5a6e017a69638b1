"""Stage 4.3's world grid and its ray walk, bit for bit (libstage/world.cc, region.hh).

The grid: cells of `resolution` metres, grouped in regions of 32 x 32 cells; a body's polygon
is put into the grid by its OUTLINE only: each vertex floored to a cell, each edge drawn as a
4-connected line that leaves out its last cell (MapPoly). Every cell keeps the blocks drawn
into it in the order they were drawn, once per layer: Stage keeps two layers so that rangers
read the previous step's bodies (layer (updates + 1) % 2) while robots move in the other.

The ray (World::Raytrace), with its quirks kept and named:
- STAGE_TRUNCATED_LOOKUP: the walk's position is a double, converted to a cell by int32
  truncation (toward zero), so below zero a ray reads the cell one step toward zero;
- STAGE_EMPTY_REGION_JUMP: through a region that holds no block in either layer the ray
  jumps from region border to region border, without updating the walk's error term;
- STAGE_WALK_RANGE: the range is |dx / cos| or |dy / sin| along the walk's major axis, to
  the walk's position in the hit cell, not to the exact crossing.

Here the grid is stored for speed, without changing what a walk sees: the regions of a
table around the world carry their block count; the cells of regions with static bodies
(bodies that never move) carry, per beam height, the first static model a beam would hit
there and, per moving body's height range, whether a static obstacle is there; moving
bodies (robots and what they carry) are kept as Stage keeps them, as ordered lists per
cell and layer. Which entry comes first in a cell is decided by when it was drawn (a
sequence number), as in Stage's per-cell vectors.
"""
import math
import os

import numpy as np

# The threads of the parallel ray cast sleep when idle: at real time stageros waits about
# 100 ms between steps, and OpenMP's default (spinning up to 300 000 times first) would burn
# part of a core meanwhile. Read by OpenMP when numba first starts its threads.
os.environ.setdefault('OMP_WAIT_POLICY', 'PASSIVE')

try:
    from numba import njit, prange
except ImportError:  # pragma: no cover - python3-numba is a dependency
    prange = range

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

RBITS = 5                    # Stage: a region is 2^5 x 2^5 cells
REGION = 1 << RBITS          # 32
REGION_CELLS = REGION * REGION
NO_SEQ = np.int64(1) << 62   # larger than any drawing's sequence number
NO_HIT = -1                  # collides(): nothing in the way
GROUND = -2                  # collides(): a block below the floor (Stage's ground model)
STATIC = -3                  # collides(): a static obstacle


@njit(cache=True)
def c_div(a, b):
    """C's integer division of a by b > 0 (truncates toward zero)."""
    return a // b if a >= 0 else -((-a) // b)


@njit(cache=True)
def trunc32(x):
    """C's (int32_t) of a double: toward zero."""
    return np.int64(x) if x >= 0.0 else -np.int64(-x)


@njit(cache=True)
def poly_cells(vx, vy, out_x, out_y, start):
    """Stage's MapPoly: the cells of a closed polygon's outline, each edge a 4-connected
    line from its first vertex's cell, not including its last; written to out[start:]
    (which must have room); returns the new end."""
    k = start
    n = vx.shape[0]
    for i in range(n):
        x0 = vx[i]
        y0 = vy[i]
        x1 = vx[(i + 1) % n]
        y1 = vy[(i + 1) % n]
        dx = x1 - x0
        dy = y1 - y0
        sx = -1 if dx < 0 else 1
        sy = -1 if dy < 0 else 1
        ax = abs(dx)
        ay = abs(dy)
        bx = 2 * ax
        by = 2 * ay
        exy = ay - ax
        steps = ax + ay
        gx = x0
        gy = y0
        while steps > 0:
            out_x[k] = gx
            out_y[k] = gy
            k += 1
            if exy < 0:
                gx += sx
                exy += by
            else:
                gy += sy
                exy -= bx
            steps -= 1
    return k


@njit(cache=True)
def poly_cell_count(vx, vy):
    n = vx.shape[0]
    total = 0
    for i in range(n):
        total += abs(vx[(i + 1) % n] - vx[i]) + abs(vy[(i + 1) % n] - vy[i])
    return total


@njit(cache=True)
def _region(gx, gy, rx0, ry0, nrx, nry):
    """Index into the region table of global cell (gx, gy), -1 outside the table."""
    tx = (gx >> RBITS) - rx0
    ty = (gy >> RBITS) - ry0
    if tx < 0 or ty < 0 or tx >= nrx or ty >= nry:
        return -1
    return ty * nrx + tx


@njit(cache=True)
def trace(ox, oy, oz, angle_in, rng, ppm, ray_class, finder_root, layer,
          rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head,
          ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr):
    """One ray as World::Raytrace casts it: (range m, hit model index or -1)."""
    globx = ox * ppm
    globy = oy * ppm
    startx = globx
    starty = globy
    angle = 1e-12 if angle_in == 0.0 else angle_in
    sina = math.sin(angle)
    cosa = math.cos(angle)
    tana = sina / cosa
    dx = ppm * rng * cosa
    dy = ppm * rng * sina
    sx = -1 if dx < 0.0 else 1
    sy = -1 if dy < 0.0 else 1
    ax = trunc32(abs(dx))
    ay = trunc32(abs(dy))
    bx = 2 * ax
    by = 2 * ay
    exy = ay - ax
    n = ax + ay
    xjumpx = float(sx * REGION)
    xjumpy = float(sx * REGION) * tana
    yjumpx = float(sy * REGION) / tana
    yjumpy = float(sy * REGION)
    xjumpdist = abs(xjumpx) + abs(xjumpy)
    yjumpdist = abs(yjumpx) + abs(yjumpy)
    xcrossx = 0.0
    xcrossy = 0.0
    ycrossx = 0.0
    ycrossy = 0.0
    dist_x = 0.0
    dist_y = 0.0
    crossings = True
    while n > 0:
        ix = trunc32(globx)      # STAGE_TRUNCATED_LOOKUP
        iy = trunc32(globy)
        reg = _region(ix, iy, rx0, ry0, nrx, nry)
        if reg >= 0 and reg_count[reg] > 0:
            crossings = True
            cx = ix & (REGION - 1)
            cy = iy & (REGION - 1)
            spage = reg_static[reg]
            dpage = reg_dyn[reg]
            while cx >= 0 and cx < REGION and cy >= 0 and cy < REGION and n > 0:
                cell = cy * REGION + cx
                best_seq = NO_SEQ
                best = -1
                if spage >= 0:
                    m = st_ray[ray_class, spage, cell]
                    if m >= 0:
                        best = m
                        best_seq = m
                if dpage >= 0:
                    e = dyn_head[dpage, layer, cell]
                    while e >= 0:
                        if ent_seq[e] < best_seq:
                            b = ent_block[e]
                            m = blk_model[b]
                            if (not (oz < blk_zmin[b] or oz > blk_zmax[b])
                                    and model_root[m] != finder_root and model_rr[m] >= 0.0):
                                best = m
                                best_seq = ent_seq[e]
                        e = ent_next[e]
                if best >= 0:
                    if ax > ay:      # STAGE_WALK_RANGE
                        return abs((globx - startx) / cosa) / ppm, best
                    return abs((globy - starty) / sina) / ppm, best
                if exy < 0:
                    globx += sx
                    exy += by
                    cx += sx
                else:
                    globy += sy
                    exy -= bx
                    cy += sy
                n -= 1
        else:                    # STAGE_EMPTY_REGION_JUMP
            if crossings:
                crossings = False
                regionx = float(c_div(ix, REGION) * REGION)
                regiony = float(c_div(iy, REGION) * REGION)
                if globx < 0.0 and ix % REGION != 0:
                    regionx -= REGION
                if globy < 0.0 and iy % REGION != 0:
                    regiony -= REGION
                xdx = (regionx - globx - 1.0) if sx < 0 else (regionx + REGION - globx)
                xdy = xdx * tana
                ydy = (regiony - globy - 1.0) if sy < 0 else (regiony + REGION - globy)
                ydx = ydy / tana
                xcrossx = globx + xdx
                xcrossy = globy + xdy
                ycrossx = globx + ydx
                ycrossy = globy + ydy
                dist_x = abs(xdx) + abs(xdy)
                dist_y = abs(ydx) + abs(ydy)
            if dist_x < dist_y:
                globx = xcrossx
                globy = xcrossy
                n = trunc32(n - dist_x)
                xcrossx += xjumpx
                xcrossy += xjumpy
                dist_y -= dist_x
                dist_x = xjumpdist
            else:
                globx = ycrossx
                globy = ycrossy
                n = trunc32(n - dist_y)
                ycrossx += yjumpx
                ycrossy += yjumpy
                dist_x -= dist_y
                dist_y = yjumpdist
    return rng, -1


@njit(cache=True)
def sample_angles(start, incr, count, out, at):
    """A sensor's ray angles as ModelRanger::Sensor::Update steps them: each ray's angle is
    rounded to a float (`float savedAngle`), and the next one is that float plus the
    increment (STAGE_FLOAT_RAY_ANGLES)."""
    a = start
    for t in range(count):
        f = np.float64(np.float32(a))
        out[at + t] = f
        a = f + incr


@njit(cache=True)
def _scan_angles(origins, incr, offsets, angles):
    for s in range(origins.shape[0]):
        sample_angles(origins[s, 3], incr[s], offsets[s + 1] - offsets[s], angles, offsets[s])


@njit(cache=True)
def _cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0, nrx,
              nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
              ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, out_range,
              out_model):
    s = sensor[k]
    r, m = trace(origins[s, 0], origins[s, 1], origins[s, 2], angles[k], rmax[s], ppm,
                 ray_class[s], root[s], layer, rx0, ry0, nrx, nry, reg_count, reg_static,
                 reg_dyn, st_ray, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                 blk_zmax, model_root, model_rr)
    out_range[k] = r
    out_model[k] = m


@njit(cache=True)
def cast_scans(origins, incr, offsets, sensor, rmax, ray_class, root, layer, ppm, rx0, ry0,
               nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
               ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, angles, out_range,
               out_model):
    """Every ray of every sensor (per sensor: its first ray's pose x, y, z, angle, its angle
    increment, its range; sensor[k] the sensor of ray k), in this thread."""
    _scan_angles(origins, incr, offsets, angles)
    for k in range(sensor.shape[0]):
        _cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0, nrx,
                  nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
                  ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, out_range,
                  out_model)


@njit(parallel=True, cache=True)
def cast_scans_parallel(origins, incr, offsets, sensor, rmax, ray_class, root, layer, ppm, rx0,
                        ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head,
                        ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
                        model_root, model_rr, angles, out_range, out_model):
    """cast_scans, the rays shared among numba's threads."""
    _scan_angles(origins, incr, offsets, angles)
    for k in prange(sensor.shape[0]):
        _cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0, nrx,
                  nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
                  ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, out_range,
                  out_model)


# ---- moving bodies: Stage's Map / UnMap / TestCollision ----------------------------------

@njit(cache=True)
def unmap_block(b, layer, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count,
                reg_dyn, reg_dyncount, dyn_head, ent_block, ent_next, free_state, ent_free,
                page_free):
    """Block::UnMap: out of every cell it was drawn into (all its entries in each), one
    count off the region per drawing."""
    s = rc_start[b]
    for k in range(rc_len[layer, b]):
        reg = _region(rc_x[layer, s + k], rc_y[layer, s + k], rx0, ry0, nrx, nry)
        page = reg_dyn[reg]
        cell = (rc_y[layer, s + k] & (REGION - 1)) * REGION + (rc_x[layer, s + k] & (REGION - 1))
        prev = -1
        e = dyn_head[page, layer, cell]
        while e >= 0:
            nxt = ent_next[e]
            if ent_block[e] == b:
                if prev < 0:
                    dyn_head[page, layer, cell] = nxt
                else:
                    ent_next[prev] = nxt
                ent_next[e] = ent_free[0]
                ent_free[0] = e
            else:
                prev = e
            e = nxt
        reg_count[reg] -= 1
        reg_dyncount[reg] -= 1
        if reg_dyncount[reg] == 0:
            page_free[free_state[0]] = page
            free_state[0] += 1
            reg_dyn[reg] = -1
    rc_len[layer, b] = 0


@njit(cache=True)
def map_block(b, layer, vx, vy, seq, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry,
              reg_count, reg_dyn, reg_dyncount, dyn_head, ent_block, ent_next, ent_seq,
              free_state, ent_free, page_free):
    """Block::Map: the block's outline cells at the given pixel vertices, each an entry at
    the end of its cell's list. The region table must hold them (World keeps it so)."""
    s = rc_start[b]
    end = poly_cells(vx, vy, rc_x[layer], rc_y[layer], s)
    rc_len[layer, b] = end - s
    for k in range(s, end):
        gx = rc_x[layer, k]
        gy = rc_y[layer, k]
        reg = _region(gx, gy, rx0, ry0, nrx, nry)
        page = reg_dyn[reg]
        if page < 0:
            free_state[0] -= 1
            page = page_free[free_state[0]]
            dyn_head[page, 0, :] = -1
            dyn_head[page, 1, :] = -1
            reg_dyn[reg] = page
        cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
        e = ent_free[0]
        ent_free[0] = ent_next[e]
        ent_block[e] = b
        ent_seq[e] = seq
        ent_next[e] = -1
        tail = dyn_head[page, layer, cell]
        if tail < 0:
            dyn_head[page, layer, cell] = e
        else:
            while ent_next[tail] >= 0:
                tail = ent_next[tail]
            ent_next[tail] = e
        reg_count[reg] += 1
        reg_dyncount[reg] += 1


@njit(cache=True)
def collides(blocks, layer, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_static,
             reg_dyn, st_coll, blk_class, dyn_head, ent_block, ent_next, blk_model, blk_zmin,
             blk_zmax, model_root, model_obstacle):
    """Block::TestCollision over `blocks` (a robot and what it carries, drawn in `layer`):
    the moving model hit, STATIC, GROUND for a block below the floor, or NO_HIT."""
    for i in range(blocks.shape[0]):
        b = blocks[i]
        m = blk_model[b]
        if not model_obstacle[m]:
            continue
        if blk_zmin[b] < 0.0:
            return GROUND
        bit = np.uint32(1) << np.uint32(blk_class[b])
        s = rc_start[b]
        for k in range(rc_len[layer, b]):
            gx = rc_x[layer, s + k]
            gy = rc_y[layer, s + k]
            reg = _region(gx, gy, rx0, ry0, nrx, nry)
            cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
            spage = reg_static[reg]
            if spage >= 0 and (st_coll[spage, cell] & bit) != 0:
                return STATIC
            page = reg_dyn[reg]
            if page >= 0:
                e = dyn_head[page, layer, cell]
                while e >= 0:
                    b2 = ent_block[e]
                    m2 = blk_model[b2]
                    if (m2 != m and model_obstacle[m2] and model_root[m2] != model_root[m]
                            and blk_zmin[b2] <= blk_zmax[b] and blk_zmax[b2] >= blk_zmin[b]):
                        return m2
                    e = ent_next[e]
    return NO_HIT


@njit(cache=True)
def _redraw(blocks, poses, seqs, layer, ppm, pts, pts_off, vx, vy, rc_start, rc_len, rc_x,
            rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount, dyn_head, ent_block,
            ent_next, ent_seq, free_state, ent_free, page_free):
    """UnMap then Map of each block at its model's body pose (x, y, cos, sin): Stage's
    LocalToPixels, floor((x + px cos - py sin) * ppm), in Stage's order of operations."""
    for i in range(blocks.shape[0]):
        b = blocks[i]
        gx, gy, cosa, sina = poses[i, 0], poses[i, 1], poses[i, 2], poses[i, 3]
        n = pts_off[b + 1] - pts_off[b]
        for j in range(n):
            px = pts[pts_off[b] + j, 0]
            py = pts[pts_off[b] + j, 1]
            vx[j] = math.floor((gx + px * cosa - py * sina) * ppm)
            vy[j] = math.floor((gy + px * sina + py * cosa) * ppm)
        unmap_block(b, layer, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count,
                    reg_dyn, reg_dyncount, dyn_head, ent_block, ent_next, free_state, ent_free,
                    page_free)
        map_block(b, layer, vx[:n], vy[:n], seqs[i], rc_start, rc_len, rc_x, rc_y, rx0, ry0,
                  nrx, nry, reg_count, reg_dyn, reg_dyncount, dyn_head, ent_block, ent_next,
                  ent_seq, free_state, ent_free, page_free)


@njit(cache=True)
def move(blocks, new_poses, old_poses, seqs, layer, ppm, pts, pts_off, vx, vy, rc_start,
         rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, reg_dyncount,
         st_coll, blk_class, dyn_head, ent_block, ent_next, ent_seq, free_state, ent_free,
         page_free, blk_model, blk_zmin, blk_zmax, model_root, model_obstacle):
    """ModelPosition::Move's grid work: the robot's blocks drawn in `layer` at their new
    poses, tested; on a collision drawn back at the old ones (seqs: two rows, the drawing
    numbers of each). Returns collides()'s answer."""
    _redraw(blocks, new_poses, seqs[0], layer, ppm, pts, pts_off, vx, vy, rc_start, rc_len,
            rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount, dyn_head,
            ent_block, ent_next, ent_seq, free_state, ent_free, page_free)
    hit = collides(blocks, layer, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry,
                   reg_static, reg_dyn, st_coll, blk_class, dyn_head, ent_block, ent_next,
                   blk_model, blk_zmin, blk_zmax, model_root, model_obstacle)
    if hit != NO_HIT:
        _redraw(blocks, old_poses, seqs[1], layer, ppm, pts, pts_off, vx, vy, rc_start,
                rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount,
                dyn_head, ent_block, ent_next, ent_seq, free_state, ent_free, page_free)
    return hit
