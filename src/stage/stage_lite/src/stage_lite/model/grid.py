"""Stage 4.3's world grid, bit for bit (libstage/world.cc, region.hh, block.cc): bodies drawn.

The grid: cells of `resolution` metres, grouped in regions of 32 x 32 cells; a body's polygon
is put into the grid by its OUTLINE only: each vertex floored to a cell, each edge drawn as a
4-connected line that leaves out its last cell (MapPoly). Every cell keeps the blocks drawn
into it in the order they were drawn, once per layer: Stage keeps two layers so that rangers
read the previous step's bodies (layer (updates + 1) % 2) while robots move in the other.
The rays that walk the grid are raytrace.py's.

Here the grid is stored for speed, without changing what a walk sees: the regions of a
table around the world carry their block count; the cells of regions with static bodies
(bodies that never move) carry, per beam height, the first static model a beam would hit
there and, per moving body's height range, whether a static obstacle is there; moving
bodies (robots and what they carry) are kept as Stage keeps them, as ordered lists per
cell and layer. Which entry comes first in a cell is decided by when it was drawn (a
sequence number), as in Stage's per-cell vectors.
"""
import math

import numpy as np

from .jit import njit

RBITS = 5                    # Stage: a region is 2^5 x 2^5 cells
REGION = 1 << RBITS          # 32
REGION_CELLS = REGION * REGION
NO_HIT = -1                  # collides(): nothing in the way
GROUND = -2                  # collides(): a block below the floor (Stage's ground model)
STATIC = -3                  # collides(): a static obstacle


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
def region_index(gx, gy, rx0, ry0, nrx, nry):
    """Index into the region table of global cell (gx, gy), -1 outside the table."""
    tx = (gx >> RBITS) - rx0
    ty = (gy >> RBITS) - ry0
    if tx < 0 or ty < 0 or tx >= nrx or ty >= nry:
        return -1
    return ty * nrx + tx


# ---- moving bodies: Stage's Map / UnMap / TestCollision ----------------------------------
# Each cell a block's outline is drawn into (its slot k in rc_x/rc_y, layer L) owns one
# entry, number L * slots + k (entries: 2 * slots, Space's): Map takes no free entry and
# UnMap finds its own without comparing blocks. An entry goes in at the head of its cell's
# list: the order within a cell is never read (a ray takes the entry drawn first by its
# sequence number, the collision test only whether any entry is in the way, the energy
# model a set).

@njit(cache=True)
def unmap_block(b, layer, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count,
                reg_dyn, reg_dyncount, dyn_head, ent_next, free_state, page_free):
    """Block::UnMap: out of every cell it was drawn into (each drawing of a cell its own
    entry), one count off the region per drawing."""
    s = rc_start[b]
    base = layer * rc_x.shape[1]
    for k in range(s, s + rc_len[layer, b]):
        gx = rc_x[layer, k]
        gy = rc_y[layer, k]
        reg = region_index(gx, gy, rx0, ry0, nrx, nry)
        page = reg_dyn[reg]
        cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
        mine = base + k
        e = dyn_head[page, layer, cell]
        if e == mine:
            dyn_head[page, layer, cell] = ent_next[e]
        else:
            while ent_next[e] != mine:
                e = ent_next[e]
            ent_next[e] = ent_next[mine]
        reg_count[reg] -= 1
        reg_dyncount[reg] -= 1
        if reg_dyncount[reg] == 0:
            page_free[free_state[0]] = page
            free_state[0] += 1
            reg_dyn[reg] = -1
    rc_len[layer, b] = 0


@njit(cache=True)
def map_block(b, layer, vx, vy, seq, test, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry,
              reg_count, reg_static, reg_dyn, reg_dyncount, st_coll, blk_class, dyn_head,
              ent_block, ent_next, ent_seq, free_state, page_free, blk_model, blk_zmin,
              blk_zmax, model_root, model_obstacle):
    """Block::Map: the block's outline cells at the given pixel vertices, an entry each.
    The region table must hold them (World keeps it so). With `test`, each cell is also
    tested as Block::TestCollision tests it (the robot's own blocks never count, so a cell
    tested as it is drawn reads what the test after the whole robot is drawn reads):
    returns collides()'s kind of answer, NO_HIT without `test`."""
    s = rc_start[b]
    end = poly_cells(vx, vy, rc_x[layer], rc_y[layer], s)
    rc_len[layer, b] = end - s
    base = layer * rc_x.shape[1]
    hit = NO_HIT
    m = root = -1
    bit = np.uint32(0)
    zmin = zmax = 0.0
    if test:        # (without it, the tables of the test may be empty: not read)
        m = blk_model[b]
        if not model_obstacle[m]:
            test = False
        elif blk_zmin[b] < 0.0:
            hit = GROUND
        bit = np.uint32(1) << np.uint32(blk_class[b])
        zmin = blk_zmin[b]
        zmax = blk_zmax[b]
        root = model_root[m]
    for k in range(s, end):
        gx = rc_x[layer, k]
        gy = rc_y[layer, k]
        reg = region_index(gx, gy, rx0, ry0, nrx, nry)
        page = reg_dyn[reg]
        if page < 0:
            free_state[0] -= 1
            page = page_free[free_state[0]]
            dyn_head[page, 0, :] = -1
            dyn_head[page, 1, :] = -1
            reg_dyn[reg] = page
        cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
        if test and hit == NO_HIT:
            spage = reg_static[reg]
            if spage >= 0 and (st_coll[spage, cell] & bit) != 0:
                hit = STATIC
            else:
                e = dyn_head[page, layer, cell]
                while e >= 0:
                    b2 = ent_block[e]
                    m2 = blk_model[b2]
                    if (m2 != m and model_obstacle[m2] and model_root[m2] != root
                            and blk_zmin[b2] <= zmax and blk_zmax[b2] >= zmin):
                        hit = m2
                        break
                    e = ent_next[e]
        e = base + k
        ent_block[e] = b
        ent_seq[e] = seq
        ent_next[e] = dyn_head[page, layer, cell]
        dyn_head[page, layer, cell] = e
        reg_count[reg] += 1
        reg_dyncount[reg] += 1
    return hit


@njit(cache=True)
def redraw(blocks, poses, seqs, layer, ppm, pts, pts_off, vx, vy, rc_start, rc_len, rc_x,
           rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount, dyn_head, ent_block,
           ent_next, ent_seq, free_state, ent_free, page_free):
    """UnMap then Map of each block at its model's body pose (x, y, cos, sin): Stage's
    LocalToPixels, floor((x + px cos - py sin) * ppm), in Stage's order of operations.
    (ent_free: unused, entries being the cells' own.)"""
    none = np.zeros(0, np.int64)
    redraw_tested(blocks, poses, seqs, layer, False, ppm, pts, pts_off, vx, vy, rc_start,
                  rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyn,
                  reg_dyncount, np.zeros((0, REGION_CELLS), np.uint32), none, dyn_head,
                  ent_block, ent_next, ent_seq, free_state, page_free, none,
                  np.zeros(0), np.zeros(0), none, np.zeros(0, np.bool_))


@njit(cache=True)
def redraw_tested(blocks, poses, seqs, layer, test, ppm, pts, pts_off, vx, vy, rc_start,
                  rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
                  reg_dyncount, st_coll, blk_class, dyn_head, ent_block, ent_next, ent_seq,
                  free_state, page_free, blk_model, blk_zmin, blk_zmax, model_root,
                  model_obstacle):
    """redraw(), each block's new cells tested as they are drawn (map_block's `test`):
    the first hit found, or NO_HIT."""
    hit = NO_HIT
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
                    reg_dyn, reg_dyncount, dyn_head, ent_next, free_state, page_free)
        still = test and hit == NO_HIT
        h = map_block(b, layer, vx[:n], vy[:n], seqs[i], still, rc_start,
                      rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
                      reg_dyncount, st_coll, blk_class, dyn_head, ent_block, ent_next,
                      ent_seq, free_state, page_free, blk_model, blk_zmin, blk_zmax,
                      model_root, model_obstacle)
        if hit == NO_HIT:
            hit = h
    return hit


@njit(cache=True)
def move(blocks, new_poses, old_poses, seqs, layer, ppm, pts, pts_off, vx, vy, rc_start,
         rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, reg_dyncount,
         st_coll, blk_class, dyn_head, ent_block, ent_next, ent_seq, free_state, ent_free,
         page_free, blk_model, blk_zmin, blk_zmax, model_root, model_obstacle):
    """ModelPosition::Move's grid work: the robot's blocks drawn in `layer` at their new
    poses, tested (Block::TestCollision: a static obstacle, the ground, or a moving model in
    the way, as drawn in that layer); on a collision drawn back at the old ones (seqs: two
    rows, the drawing numbers of each). Returns NO_HIT or one thing in the way (which one
    is not Stage's: only whether there is one is read). ent_free: unused."""
    hit = redraw_tested(blocks, new_poses, seqs[0], layer, True, ppm, pts, pts_off, vx, vy,
                        rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count,
                        reg_static, reg_dyn, reg_dyncount, st_coll, blk_class, dyn_head,
                        ent_block, ent_next, ent_seq, free_state, page_free, blk_model,
                        blk_zmin, blk_zmax, model_root, model_obstacle)
    if hit != NO_HIT:
        redraw_tested(blocks, old_poses, seqs[1], layer, False, ppm, pts, pts_off, vx, vy,
                      rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static,
                      reg_dyn, reg_dyncount, st_coll, blk_class, dyn_head, ent_block,
                      ent_next, ent_seq, free_state, page_free, blk_model, blk_zmin,
                      blk_zmax, model_root, model_obstacle)
    return hit
