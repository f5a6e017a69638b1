"""Stage 4.3's ray walk through the grid, bit for bit (libstage/world.cc's World::Raytrace).

A ray walks grid.py's cells, with its quirks kept and named:
- STAGE_TRUNCATED_LOOKUP: the walk's position is a double, converted to a cell by int32
  truncation (toward zero), so below zero a ray reads the cell one step toward zero;
- STAGE_EMPTY_REGION_JUMP: through a region that holds no block in either layer the ray
  jumps from region border to region border, without updating the walk's error term;
- STAGE_WALK_RANGE: the range is |dx / cos| or |dy / sin| along the walk's major axis, to
  the walk's position in the hit cell, not to the exact crossing;
- STAGE_FLOAT_RAY_ANGLES: each beam's angle is rounded to a float, the next one being that
  float plus the increment.
A cell's first entry is its first static model (for the beam's height) or the moving block
drawn first, whichever was drawn first (sequence numbers, as Stage's per-cell vectors).
"""
import math

import numpy as np

from .grid import REGION, region_index
from .jit import kernel, njit, prange

NO_SEQ = np.int64(1) << 62   # larger than any drawing's sequence number


@kernel
def c_div(a, b):
    """C's integer division of a by b > 0 (truncates toward zero)."""
    return a // b if a >= 0 else -((-a) // b)


@kernel
def trunc32(x):
    """C's (int32_t) of a double: toward zero."""
    return np.int64(x) if x >= 0.0 else -np.int64(-x)


@kernel
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
        reg = region_index(ix, iy, rx0, ry0, nrx, nry)
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
                    # the list is in drawing order (grid.py): its first entry in the way
                    # is the first drawn, unless the static one came before it
                    e = dyn_head[dpage, layer, cell]
                    while e >= 0 and ent_seq[e] < best_seq:
                        b = ent_block[e]
                        m = blk_model[b]
                        if (not (oz < blk_zmin[b] or oz > blk_zmax[b])
                                and model_root[m] != finder_root and model_rr[m] >= 0.0):
                            best = m
                            break
                        e = ent_next[e]
                if best >= 0:
                    if ax > ay:      # STAGE_WALK_RANGE
                        return abs((globx - startx) / cosa) / ppm, best
                    return abs((globy - starty) / sina) / ppm, best
                # one step along x or y, without a branch (the choice follows the
                # angle's fraction and is mispredicted about half the time)
                tx = np.int64(exy < 0)
                ty = 1 - tx
                globx += sx * tx
                globy += sy * ty
                exy += by * tx - bx * ty
                cx += sx * tx
                cy += sy * ty
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


@kernel
def sample_angles(start, incr, count, out, at):
    """A sensor's ray angles as ModelRanger::Sensor::Update steps them: each ray's angle is
    rounded to a float (`float savedAngle`), and the next one is that float plus the
    increment (STAGE_FLOAT_RAY_ANGLES)."""
    a = start
    for t in range(count):
        f = np.float64(np.float32(a))
        out[at + t] = f
        a = f + incr


@kernel
def scan_angles(origins, incr, offsets, angles):
    """Every sensor's ray angles (sample_angles), from its offset in angles on."""
    for s in range(origins.shape[0]):
        sample_angles(origins[s, 3], incr[s], offsets[s + 1] - offsets[s], angles, offsets[s])


@kernel
def cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0, nrx,
             nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
             ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, out_range,
             out_model):
    """Ray k (of sensor sensor[k], at angles[k]) cast: its range and the model it hit (or
    -1) into out_range[k] and out_model[k]."""
    s = sensor[k]
    r, m = trace(origins[s, 0], origins[s, 1], origins[s, 2], angles[k], rmax[s], ppm,
                 ray_class[s], root[s], layer, rx0, ry0, nrx, nry, reg_count, reg_static,
                 reg_dyn, st_ray, dyn_head, ent_block, ent_next, ent_seq, blk_model, blk_zmin,
                 blk_zmax, model_root, model_rr)
    out_range[k] = r
    out_model[k] = m


@kernel
def cast_scans(origins, incr, offsets, sensor, rmax, ray_class, root, layer, ppm, rx0, ry0,
               nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
               ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, angles, out_range,
               out_model):
    """Every ray of every sensor (per sensor: its first ray's pose x, y, z, angle, its angle
    increment, its range; sensor[k] the sensor of ray k), in this thread."""
    scan_angles(origins, incr, offsets, angles)
    for k in range(sensor.shape[0]):
        cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0, nrx,
                 nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
                 ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, out_range,
                 out_model)


@njit(parallel=True, cache=True)
def cast_scans_parallel(origins, incr, offsets, sensor, rmax, ray_class, root, layer, ppm, rx0,
                        ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head,
                        ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax,
                        model_root, model_rr, angles, out_range, out_model):
    """cast_scans, the rays shared among numba's threads."""
    scan_angles(origins, incr, offsets, angles)
    for k in prange(sensor.shape[0]):
        cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0, nrx,
                 nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block, ent_next,
                 ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr, out_range,
                 out_model)
