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
bodies (robots and what they carry) are kept as Stage keeps them, as lists per cell and
layer in the order they were drawn, as Stage's per-cell vectors: a drawing joins the end of
its cells' lists, and its number (a sequence number) is above every earlier drawing's
(robots moved two at a time included: motion.plan_apart), so a list is in number order too,
which the ray walk relies on (raytrace.trace). The lists are linked both ways (a head's
previous entry is its list's tail), so that an entry joins or leaves a list in one step
however long the list: a crowd on one spot costs what a spread swarm does.
"""
import math

import numpy as np

from .jit import kernel, unsigned

RBITS = 5                    # Stage: a region is 2^5 x 2^5 cells
REGION = 1 << RBITS          # 32
REGION_CELLS = REGION * REGION
NO_HIT = -1                  # collides(): nothing in the way
GROUND = -2                  # collides(): a block below the floor (Stage's ground model)
STATIC = -3                  # collides(): a static obstacle


@kernel
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


@kernel
def poly_cell_count(vx, vy):
    n = vx.shape[0]
    total = 0
    for i in range(n):
        total += abs(vx[(i + 1) % n] - vx[i]) + abs(vy[(i + 1) % n] - vy[i])
    return total


@kernel
def region_index(gx, gy, rx0, ry0, nrx, nry):
    """Index into the region table of global cell (gx, gy), -1 outside the table."""
    tx = (gx >> RBITS) - rx0
    ty = (gy >> RBITS) - ry0
    if tx < 0 or ty < 0 or tx >= nrx or ty >= nry:
        return -1
    return ty * nrx + tx


# ---- moving bodies: Stage's Map / UnMap / TestCollision ----------------------------------

@kernel
def entry_of(layer, k, rc_x):
    """The entry of a drawing's cell rc_x[layer, k]: one per cell a block's drawing can
    take, in each layer."""
    return layer * rc_x.shape[1] + k


@kernel
def hold_page(reg, reg_dyn, dyn_head, free_state, page_free):
    """The page of region reg's moving bodies, taken from the pool if it has none (the pool
    must have one)."""
    page = reg_dyn[unsigned(reg)]
    if page < 0:
        free_state[0] -= 1
        page = page_free[free_state[0]]
        dyn_head[page, 0, :] = -1
        dyn_head[page, 1, :] = -1
        reg_dyn[unsigned(reg)] = page
    return page


@kernel
def unmap_block(b, layer, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count,
                reg_dyn, reg_dyncount, dyn_head, ent_next, ent_prev, free_state, page_free):
    """Block::UnMap: out of every cell it was drawn into (each of its entries unlinked from
    its cell's list, the others kept in order), one count off the region per drawing; a
    region's page back to the pool when its last entry goes."""
    s = rc_start[unsigned(b)]
    for k in range(rc_len[unsigned(layer), unsigned(b)]):
        gx = rc_x[unsigned(layer), unsigned(s + k)]
        gy = rc_y[unsigned(layer), unsigned(s + k)]
        reg = region_index(gx, gy, rx0, ry0, nrx, nry)
        page = reg_dyn[unsigned(reg)]
        cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
        e = entry_of(layer, s + k, rc_x)
        nxt = ent_next[unsigned(e)]
        prv = ent_prev[unsigned(e)]
        head = dyn_head[unsigned(page), unsigned(layer), unsigned(cell)]
        if e == head:
            dyn_head[unsigned(page), unsigned(layer), unsigned(cell)] = nxt
            if nxt >= 0:
                ent_prev[unsigned(nxt)] = prv          # the new head keeps the tail
        else:
            ent_next[unsigned(prv)] = nxt
            if nxt >= 0:
                ent_prev[unsigned(nxt)] = prv
            else:
                ent_prev[unsigned(head)] = prv         # e was the tail
        reg_count[unsigned(reg)] -= 1
        reg_dyncount[unsigned(reg)] -= 1
        if reg_dyncount[unsigned(reg)] == 0:
            page_free[free_state[0]] = page
            free_state[0] += 1
            reg_dyn[unsigned(reg)] = -1
    rc_len[unsigned(layer), unsigned(b)] = 0


@kernel
def map_block(b, layer, vx, vy, seq, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry,
              reg_count, reg_dyn, reg_dyncount, dyn_head, ent_block, ent_next, ent_prev,
              ent_seq, free_state, page_free, test, reg_static, st_coll, blk_class, blk_model,
              blk_zmin, blk_zmax, model_root, model_obstacle):
    """Block::Map: the block's outline cells at the given pixel vertices, each an entry at
    the end of its cell's list. The region table must hold them (World keeps it so). A
    drawing's k-th cell is entry k of its layer's row (entry_of): each block owns its
    entries, so that robots far apart can be drawn at once (motion.move_apart). With
    `test`, also the block's part of collides() on the way (its cells, static first, then
    each cell's list from its head): its robot's own entries never count there,
    and nothing else changes while its robot is drawn, so this is what collides() would say
    of the block once its robot is drawn. Returns that (NO_HIT without `test`)."""
    s = rc_start[unsigned(b)]
    end = poly_cells(vx, vy, rc_x[layer], rc_y[layer], s)
    rc_len[unsigned(layer), unsigned(b)] = end - s
    m = blk_model[b]
    testing = test and model_obstacle[m]
    hit = NO_HIT
    if testing and blk_zmin[b] < 0.0:
        hit = GROUND
        testing = False
    bit = np.uint32(1) << np.uint32(blk_class[b])
    for k in range(s, end):
        gx = rc_x[unsigned(layer), unsigned(k)]
        gy = rc_y[unsigned(layer), unsigned(k)]
        reg = region_index(gx, gy, rx0, ry0, nrx, nry)
        page = hold_page(reg, reg_dyn, dyn_head, free_state, page_free)
        cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
        if testing:
            spage = reg_static[unsigned(reg)]
            if spage >= 0 and (st_coll[unsigned(spage), unsigned(cell)] & bit) != 0:
                hit = STATIC
                testing = False
        e = entry_of(layer, k, rc_x)
        ent_block[unsigned(e)] = b
        ent_seq[unsigned(e)] = seq
        ent_next[unsigned(e)] = -1
        head = dyn_head[unsigned(page), unsigned(layer), unsigned(cell)]
        if head < 0:
            dyn_head[unsigned(page), unsigned(layer), unsigned(cell)] = e
            ent_prev[unsigned(e)] = e
        else:
            if testing:
                other = head
                while other >= 0:
                    if _blocks(m, b, ent_block[unsigned(other)], blk_model, blk_zmin, blk_zmax,
                               model_root, model_obstacle):
                        hit = blk_model[ent_block[unsigned(other)]]
                        testing = False
                        break
                    other = ent_next[unsigned(other)]
            tail = ent_prev[unsigned(head)]
            ent_next[unsigned(tail)] = e
            ent_prev[unsigned(e)] = tail
            ent_prev[unsigned(head)] = e
        reg_count[unsigned(reg)] += 1
        reg_dyncount[unsigned(reg)] += 1
    return hit


@kernel
def _blocks(m, b, b2, blk_model, blk_zmin, blk_zmax, model_root, model_obstacle):
    """Whether block b2 stands in the way of block b (of model m): Block::TestCollision's
    rule (another obstacle model of another tree, their height ranges meeting)."""
    m2 = blk_model[b2]
    return (m2 != m and model_obstacle[m2] and model_root[m2] != model_root[m]
            and blk_zmin[b2] <= blk_zmax[b] and blk_zmax[b2] >= blk_zmin[b])


@kernel
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
        s = rc_start[unsigned(b)]
        for k in range(rc_len[unsigned(layer), unsigned(b)]):
            gx = rc_x[unsigned(layer), unsigned(s + k)]
            gy = rc_y[unsigned(layer), unsigned(s + k)]
            reg = region_index(gx, gy, rx0, ry0, nrx, nry)
            cell = (gy & (REGION - 1)) * REGION + (gx & (REGION - 1))
            spage = reg_static[unsigned(reg)]
            if spage >= 0 and (st_coll[unsigned(spage), unsigned(cell)] & bit) != 0:
                return STATIC
            page = reg_dyn[unsigned(reg)]
            if page >= 0:
                e = dyn_head[unsigned(page), unsigned(layer), unsigned(cell)]
                while e >= 0:
                    if _blocks(m, b, ent_block[unsigned(e)], blk_model, blk_zmin, blk_zmax,
                               model_root, model_obstacle):
                        return blk_model[ent_block[unsigned(e)]]
                    e = ent_next[unsigned(e)]
    return NO_HIT


@kernel
def redraw(blocks, poses, seqs, layer, ppm, pts, pts_off, vx, vy, rc_start, rc_len, rc_x,
           rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount, dyn_head, ent_block,
           ent_next, ent_prev, ent_seq, free_state, page_free, test, reg_static, st_coll,
           blk_class, blk_model, blk_zmin, blk_zmax, model_root, model_obstacle):
    """UnMap then Map of each block at its model's body pose (x, y, cos, sin): Stage's
    LocalToPixels, floor((x + px cos - py sin) * ppm), in Stage's order of operations. With
    `test`, the blocks (a robot and what it carries) also tested as they are drawn: what
    collides() would then say (map_block), else NO_HIT."""
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
                    reg_dyn, reg_dyncount, dyn_head, ent_next, ent_prev, free_state,
                    page_free)
        testing = test and hit == NO_HIT     # (the first hit is the answer)
        found = map_block(b, layer, vx[:n], vy[:n], seqs[i], rc_start, rc_len, rc_x, rc_y,
                          rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount, dyn_head,
                          ent_block, ent_next, ent_prev, ent_seq, free_state, page_free,
                          testing, reg_static, st_coll, blk_class, blk_model,
                          blk_zmin, blk_zmax, model_root, model_obstacle)
        if hit == NO_HIT:
            hit = found
    return hit


@kernel
def move(blocks, new_poses, old_poses, seqs, layer, ppm, pts, pts_off, vx, vy, rc_start,
         rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, reg_dyncount,
         st_coll, blk_class, dyn_head, ent_block, ent_next, ent_prev, ent_seq, free_state,
         page_free, blk_model, blk_zmin, blk_zmax, model_root, model_obstacle):
    """ModelPosition::Move's grid work: the robot's blocks drawn in `layer` at their new
    poses and tested as they are drawn (redraw's test: collides()'s answer, without a
    second walk of the cells); on a collision drawn back at the old ones (seqs: two rows,
    the drawing numbers of each). Returns collides()'s answer."""
    hit = redraw(blocks, new_poses, seqs[0], layer, ppm, pts, pts_off, vx, vy, rc_start,
                 rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount,
                 dyn_head, ent_block, ent_next, ent_prev, ent_seq, free_state, page_free,
                 True, reg_static, st_coll, blk_class, blk_model, blk_zmin, blk_zmax, model_root,
                 model_obstacle)
    if hit != NO_HIT:
        redraw(blocks, old_poses, seqs[1], layer, ppm, pts, pts_off, vx, vy, rc_start,
               rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_dyn, reg_dyncount,
               dyn_head, ent_block, ent_next, ent_prev, ent_seq, free_state, page_free,
               False, reg_static, st_coll, blk_class, blk_model, blk_zmin, blk_zmax, model_root,
               model_obstacle)
    return hit
