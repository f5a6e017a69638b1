"""Every robot's update and move in one kernel each, Stage's rules in Stage's order (no rospy).

ModelPosition::Update (the goal turned into the velocity, the estimate) and
ModelPosition::Move (the move, drawn in the grid, undone on a collision) for all the robots
of a step, on the world's RobotArrays (robot_state.py), and the world poses of what the
robots carry (their bodies' frames, their sensors' first rays) from the robots' poses.
Each is the World's per-robot Python (world.py) operation for operation: pose sums in
Stage's order (pose.py), cos and sin from the same C library, so every double is the same.
The World uses them when every robot is a top-level model (its pose is its world pose);
a robot on another model moves the World's own way.

Stage moves its robots one after another in its main thread. Two robots' moves commute when
neither can touch a cell the other's touches, so with many robots the moves are split
(plan_apart) into two sides of a line across the grid, moved at once in two threads
(move_robots, without the GIL), and a rest moved after them in turn: the same grid, poses
and stalls as in turn, on every machine.
"""
import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import grid
from .jit import kernel, njit, numba_threads, unsigned
from .robot_state import MODE_CODE

VELOCITY = MODE_CODE['velocity']
ACCELERATION = MODE_CODE['acceleration']
DIFF, OMNI, CAR = 0, 1, 2
DRIVES = {'diff': DIFF, 'omni': OMNI, 'car': CAR}
#: A move's cost besides its outline's cells (its bodies' poses, the tried pose), in cells
MOVE_CELLS = 20
#: From this much work in a step's moves (move_work: about 1.5 ms on this project's
#: machines), the robots far apart are moved two at a time (plan_apart); below it, planning
#: and waking a thread (about 0.15 ms asleep) cost more than they save.
APART_CELLS = 15000


@kernel
def normalize(a):
    """pose.stage_normalize."""
    while a < -math.pi:
        a += 2.0 * math.pi
    while a > math.pi:
        a -= 2.0 * math.pi
    return a


@kernel
def pose_add(px, py, pz, pa, qx, qy, qz, qa):
    """pose.pose_add."""
    return pose_add_turned(px, py, pz, pa, math.cos(pa), math.sin(pa), qx, qy, qz, qa)


@kernel
def pose_add_turned(px, py, pz, pa, cosa, sina, qx, qy, qz, qa):
    """pose_add with cos(pa) and sin(pa) given (computed once for poses added to one)."""
    return (px + qx * cosa - qy * sina, py + qx * sina + qy * cosa, pz + qz,
            normalize(pa + qa))


@kernel
def chain(pose, i, el_pose, el_stack, el_zadd, start, end):
    """Robot i's pose carried through the elements start..end: each a pose added (as
    Model::GetGlobalPose adds a child's pose to its parent's), then, where el_stack says,
    the parent's height added to z (stack_children)."""
    x, y, z, a = pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3]
    for k in range(start, end):
        x, y, z, a = pose_add(x, y, z, a, el_pose[k, 0], el_pose[k, 1], el_pose[k, 2],
                              el_pose[k, 3])
        if el_stack[k]:
            z += el_zadd[k]
    return x, y, z, a


@kernel
def chain_poses(targets, t_robot, t_off, t_shared, t_prefix, el_pose, el_stack, el_zadd, pose,
                out):
    """out[i] = the pose of target targets[i] (its robot's pose through its elements). Targets
    that share their first t_prefix elements (the same t_shared >= 0, one after the other)
    compute them once: the same sums, the same numbers."""
    last = -1
    px = py = pz = pa = 0.0
    cosa = 1.0
    sina = 0.0
    for i in range(targets.shape[0]):
        t = targets[i]
        start = t_off[t] + t_prefix[t]
        if t_shared[t] < 0 or t_shared[t] != last:
            px, py, pz, pa = chain(pose, t_robot[t], el_pose, el_stack, el_zadd, t_off[t], start)
            cosa = math.cos(pa)     # the first sum after the shared part turns by pa
            sina = math.sin(pa)
            last = t_shared[t]
        x, y, z, a = px, py, pz, pa
        for k in range(start, t_off[t + 1]):
            if k == start:
                x, y, z, a = pose_add_turned(x, y, z, a, cosa, sina, el_pose[k, 0],
                                             el_pose[k, 1], el_pose[k, 2], el_pose[k, 3])
            else:
                x, y, z, a = pose_add(x, y, z, a, el_pose[k, 0], el_pose[k, 1],
                                      el_pose[k, 2], el_pose[k, 3])
            if el_stack[k]:
                z += el_zadd[k]
        out[i, 0] = x
        out[i, 1] = y
        out[i, 2] = z
        out[i, 3] = a


@kernel
def _clamp(v, lo, hi):
    return lo if v < lo else (hi if v > hi else v)


@kernel
def _bounded(v, lo, hi):
    """Python's min(max(v, lo), hi), ties and signed zeros included."""
    v = lo if lo > v else v
    return hi if hi < v else v


@njit(cache=True)
def update_positions(due, subscribed, goal, mode, velocity, est, pose, drive, wheelbase,
                     vbounds, abounds, gps, error, given, given_velocity, dt):
    """ModelPosition::Update of the robots `due` (world.World._update_position): while
    subscribed the goal turned into the velocity (robots in `given` take given_velocity,
    position control's, computed by Robot.commanded_velocity) within vbounds; then the
    estimate: the pose (gps) or the velocity integrated with the odometry error."""
    v = np.zeros(4)
    for j in range(due.shape[0]):
        i = due[j]
        if subscribed[i]:
            gx, gy, ga = goal[i, 0], goal[i, 1], goal[i, 3]
            if given[i]:
                for k in range(4):
                    v[k] = given_velocity[i, k]
            elif mode[i] == ACCELERATION:
                gx = _bounded(gx, abounds[i, 0, 0], abounds[i, 0, 1])
                gy = _bounded(gy, abounds[i, 1, 0], abounds[i, 1, 1])
                ga = _bounded(ga, abounds[i, 3, 0], abounds[i, 3, 1])
                for k in range(4):
                    v[k] = velocity[i, k]
                if drive[i] == OMNI:
                    v[0] = v[0] + gx * dt
                    v[1] = v[1] + gy * dt
                    v[3] = v[3] + ga * dt
                elif drive[i] != CAR:
                    v[0] = v[0] + gx * dt
                    v[1] = 0.0
                    v[3] = v[3] + ga * dt
            elif drive[i] == OMNI:
                v[0], v[1], v[2], v[3] = gx, gy, 0.0, ga
            elif drive[i] == CAR:
                v[0], v[1], v[2] = gx * math.cos(ga), 0.0, 0.0
                v[3] = gx * math.sin(ga) / wheelbase[i]
            else:
                v[0], v[1], v[2], v[3] = gx, 0.0, 0.0, ga
            for k in range(4):
                v[k] = _clamp(v[k], vbounds[i, k, 0], vbounds[i, k, 1])
                velocity[i, k] = v[k]
        else:
            for k in range(4):
                v[k] = 0.0
        if gps[i]:
            for k in range(4):
                est[i, k] = pose[i, k]
        else:
            est[i, 0], est[i, 1], est[i, 3] = odometry_step(
                est[i, 0], est[i, 1], est[i, 3], v[0], v[1], v[3], dt, error[i, 0],
                error[i, 1], error[i, 3])


@kernel
def odometry_step(x, y, a, vx, vy, va, dt, ex, ey, ea):
    """ModelPosition::Update's odometry: the estimate (x, y, a) moved by the velocity over
    dt with the integration error (ex, ey, ea); the new (x, y, a)."""
    a = normalize(a + (va * dt) * (1.0 + ea))
    cosa = math.cos(a)
    sina = math.sin(a)
    dx = (vx * dt) * (1.0 + ex)
    dy = (vy * dt) * (1.0 + ey)
    x += dx * cosa + dy * sina
    y -= dy * cosa - dx * sina      # Stage's sign, kept (STAGE_ODOM_Y_SIGN)
    return x, y, a


@kernel
def _body_rows(i, pose, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd, rows):
    """World._body_rows: per block of robot i's tree, its model's body (x, y, cos, sin)."""
    n = 0
    for b in range(r_bm_off[i], r_bm_off[i + 1]):
        x, y, _, a = chain(pose, i, el_pose, el_stack, el_zadd, t_off[b], t_off[b + 1])
        c = math.cos(a)
        s = math.sin(a)
        for _k in range(bm_nblk[b]):
            rows[n, 0] = x
            rows[n, 1] = y
            rows[n, 2] = c
            rows[n, 3] = s
            n += 1


@kernel
def _outside(rows, nb, blocks, blk_radius, ppm, rx0, ry0, nrx, nry, box):
    """Space.hold's test: whether robot's blocks at these body rows could reach out of the
    region table; box gets the cell box Space.resize then takes."""
    x0 = y0 = math.inf
    x1 = y1 = -math.inf
    for k in range(nb):
        r = blk_radius[blocks[k]] * ppm + 2
        xs = rows[k, 0] * ppm
        ys = rows[k, 1] * ppm
        x0 = min(x0, xs - r)
        x1 = max(x1, xs + r)
        y0 = min(y0, ys - r)
        y1 = max(y1, ys + r)
    box[0] = int(math.floor(x0))
    box[1] = int(math.floor(y0))
    box[2] = int(math.ceil(x1))
    box[3] = int(math.ceil(y1))
    return ((box[0] >> grid.RBITS) < rx0 or (box[1] >> grid.RBITS) < ry0
            or (box[2] >> grid.RBITS) >= rx0 + nrx or (box[3] >> grid.RBITS) >= ry0 + nry)


@kernel
def _draws(i, subscribed, velocity, r_blk_off):
    """Whether robot i's move this step draws it in the grid: subscribed, with a speed,
    with blocks."""
    return (subscribed[i] and r_blk_off[i + 1] > r_blk_off[i]
            and (velocity[i, 0] != 0.0 or velocity[i, 1] != 0.0 or velocity[i, 2] != 0.0
                 or velocity[i, 3] != 0.0))


@kernel
def seq_bases(subscribed, velocity, r_bm_off, r_blk_off, seq, bases):
    """bases[i]: the drawing number robot i's move counts on from, the moves taken in order,
    each move that draws taking two per body of the robot (its tried drawing's, then its
    drawing back's, whether it is drawn back or not). Returns the last number taken."""
    for i in range(bases.shape[0]):
        bases[i] = seq
        if _draws(i, subscribed, velocity, r_blk_off):
            seq += 2 * (r_bm_off[i + 1] - r_bm_off[i])
    return seq


@kernel
def move_work(subscribed, velocity, r_blk_off, r_blocks, rc_len, layer):
    """What a step's moves will cost, in outline cells: per robot whose move draws, the
    cells of its outline in `layer` (those it erases, about as many as it draws) and
    MOVE_CELLS."""
    work = 0
    for i in range(r_blk_off.shape[0] - 1):
        if _draws(i, subscribed, velocity, r_blk_off):
            work += MOVE_CELLS
            for k in range(r_blk_off[i], r_blk_off[i + 1]):
                work += rc_len[layer, r_blocks[k]]
    return work


@kernel
def _tried(pose, velocity, i, dt):
    """Robot i's pose after a step at its velocity (the move it tries)."""
    return pose_add(pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3], velocity[i, 0] * dt,
                    velocity[i, 1] * dt, velocity[i, 2] * dt, normalize(velocity[i, 3] * dt))


@kernel
def _move_one(i, base, check, subscribed, velocity, pose, stalled, twist, dt, layer, r_bm_off,
              bm_nblk, t_off, el_pose, el_stack, el_zadd, r_blk_off, r_blocks, new_rows,
              old_rows, seqs, box, blk_radius, blk_pages, ppm, pts, pts_off, vx, vy, rc_start,
              rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn,
              reg_dyncount, st_coll, blk_class, dyn_head, ent_block, ent_next, ent_prev, ent_seq,
              free_state, page_free, blk_model, blk_zmin, blk_zmax, model_root, model_obstacle):
    """World._move of robot i, then its ground truth's twist; its drawings numbered from
    `base` (seq_bases). With `check`, first whether the move may need more free pages than
    the pool has or a larger region table (box: the cells it must hold): then nothing is
    done and the answer is False."""
    ox, oy, oa = pose[i, 0], pose[i, 1], pose[i, 3]
    if subscribed[i] and (velocity[i, 0] != 0.0 or velocity[i, 1] != 0.0
                          or velocity[i, 2] != 0.0 or velocity[i, 3] != 0.0):
        sx, sy, sz, sa = pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3]
        b0 = r_blk_off[i]
        nb = r_blk_off[i + 1] - b0
        if nb == 0:
            pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = _tried(pose, velocity, i, dt)
            stalled[i] = False
        else:
            _body_rows(i, pose, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd,
                       old_rows)
            pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = _tried(pose, velocity, i, dt)
            _body_rows(i, pose, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd,
                       new_rows)
            blocks = r_blocks[b0:b0 + nb]
            if check:
                need = 0
                for k in range(nb):
                    need += blk_pages[blocks[k]]
                if need > free_state[0] or _outside(new_rows, nb, blocks, blk_radius, ppm,
                                                    rx0, ry0, nrx, nry, box):
                    pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = sx, sy, sz, sa
                    return False
            bodies = r_bm_off[i + 1] - r_bm_off[i]
            for row in range(2):
                n = 0
                seq = base + row * bodies
                for b in range(r_bm_off[i], r_bm_off[i + 1]):
                    seq += 1
                    for _k in range(bm_nblk[b]):
                        seqs[row, n] = seq
                        n += 1
            hit = grid.move(blocks, new_rows[:nb], old_rows[:nb], seqs[:, :nb], layer, ppm,
                            pts, pts_off, vx, vy, rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx,
                            nry, reg_count, reg_static, reg_dyn, reg_dyncount, st_coll,
                            blk_class, dyn_head, ent_block, ent_next, ent_prev, ent_seq, free_state,
                            page_free, blk_model, blk_zmin, blk_zmax, model_root,
                            model_obstacle)
            if hit != grid.NO_HIT:
                pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = sx, sy, sz, sa
                stalled[i] = True
            else:
                stalled[i] = False
    twist[i, 0] = (pose[i, 0] - ox) / dt
    twist[i, 1] = (pose[i, 1] - oy) / dt
    twist[i, 2] = normalize(pose[i, 3] - oa) / dt
    return True


@kernel(nogil=True)
def move_robots(order, first, check, bases, subscribed, velocity, pose, stalled, twist, dt,
                layer, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd, r_blk_off, r_blocks,
                new_rows, old_rows, seqs, box, blk_radius, blk_pages, ppm, pts, pts_off, vx, vy,
                rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static,
                reg_dyn, reg_dyncount, st_coll, blk_class, dyn_head, ent_block, ent_next, ent_prev,
                ent_seq, free_state, page_free, blk_model, blk_zmin, blk_zmax, model_root,
                model_obstacle):
    """World.step's moves of the robots order[first:], in turn (_move_one). Returns -1
    when done, or (with `check`) the place in `order` of the robot whose move needs more
    free pages (Space.pages_short) or a larger region table (box: the cells it must hold);
    nothing of its move done yet. Without the GIL: plan_apart's two sides move at once,
    each in its own thread, without `check` (the plan has made room for them)."""
    for j in range(first, order.shape[0]):
        i = order[j]
        if not _move_one(i, bases[i], check, subscribed, velocity, pose, stalled, twist, dt,
                         layer, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd,
                         r_blk_off, r_blocks, new_rows, old_rows, seqs, box, blk_radius,
                         blk_pages, ppm, pts, pts_off, vx, vy, rc_start, rc_len, rc_x, rc_y,
                         rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, reg_dyncount,
                         st_coll, blk_class, dyn_head, ent_block, ent_next, ent_prev, ent_seq,
                         free_state, page_free, blk_model, blk_zmin, blk_zmax, model_root,
                         model_obstacle):
            return j
    return -1


@kernel
def _cell_box(i, pose, velocity, dt, layer, r_bm_off, bm_nblk, t_off, el_pose, el_stack,
              el_zadd, r_blk_off, r_blocks, rows, blk_radius, ppm, rc_start, rc_len, rc_x, rc_y,
              out):
    """out: the cells (x0, y0, x1, y1) robot i's move may touch: its drawing in `layer`
    (erased), at its pose now and at the pose it tries (Space.hold's bound of a drawing)."""
    x0 = y0 = 1 << 62
    x1 = y1 = -(1 << 62)
    for k in range(r_blk_off[i], r_blk_off[i + 1]):
        b = r_blocks[k]
        s = rc_start[b]
        for c in range(s, s + rc_len[layer, b]):
            gx = rc_x[unsigned(layer), unsigned(c)]
            gy = rc_y[unsigned(layer), unsigned(c)]
            x0 = min(x0, gx)
            x1 = max(x1, gx)
            y0 = min(y0, gy)
            y1 = max(y1, gy)
    keep = (pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3])
    nb = r_blk_off[i + 1] - r_blk_off[i]
    for tried in range(2):
        if tried:
            pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = _tried(pose, velocity, i, dt)
        _body_rows(i, pose, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd, rows)
        _outside(rows, nb, r_blocks[r_blk_off[i]:r_blk_off[i + 1]], blk_radius, ppm, 0, 0, 0,
                 0, out)     # (its box only)
        x0, y0, x1, y1 = min(x0, out[0]), min(y0, out[1]), max(x1, out[2]), max(y1, out[3])
    pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = keep
    out[0], out[1], out[2], out[3] = x0, y0, x1, y1


@kernel
def _sides(cells, boxes, draws, weight, axis, split, head, entry_robot, entry_next, touched,
           rx0, ry0, nrx, side):
    """side[i] for a split of the regions at `split` along `axis` (0: x, 1: y): 0 for a
    robot whose regions (boxes) are all below it, 1 all at or above it, 2 for the rest:
    robots across it, robots whose moves do not draw (draws[i] False), and, in order, a
    robot whose cells may meet those of one of the rest before it (it must move after
    that one). head (per region, -1), entry_robot, entry_next: the rest's robots by
    region, left empty. Returns the weights of sides 0 and 1 and of the rest's robots
    that draw."""
    w0 = w1 = w2 = 0
    entries = 0
    n_touched = 0
    for i in range(cells.shape[0]):
        if not draws[i]:
            side[i] = 2
            continue
        if boxes[i, axis + 2] < split:
            side[i] = 0
        elif boxes[i, axis] >= split:
            side[i] = 1
        else:
            side[i] = 2
        for ty in range(boxes[i, 1] - ry0, boxes[i, 3] - ry0 + 1):
            for tx in range(boxes[i, 0] - rx0, boxes[i, 2] - rx0 + 1):
                reg = ty * nrx + tx
                e = head[reg]
                while e >= 0 and side[i] < 2:
                    s = entry_robot[e]
                    if (cells[s, 0] <= cells[i, 2] and cells[i, 0] <= cells[s, 2]
                            and cells[s, 1] <= cells[i, 3] and cells[i, 1] <= cells[s, 3]):
                        side[i] = 2
                    e = entry_next[e]
        if side[i] == 2:
            for ty in range(boxes[i, 1] - ry0, boxes[i, 3] - ry0 + 1):
                for tx in range(boxes[i, 0] - rx0, boxes[i, 2] - rx0 + 1):
                    reg = ty * nrx + tx
                    if head[reg] < 0:
                        touched[n_touched] = reg
                        n_touched += 1
                    entry_robot[entries] = i
                    entry_next[entries] = head[reg]
                    head[reg] = entries
                    entries += 1
            w2 += weight[i]
        elif side[i] == 0:
            w0 += weight[i]
        else:
            w1 += weight[i]
    for j in range(n_touched):
        head[touched[j]] = -1
    return w0, w1, w2


@njit(cache=True)
def plan_apart(subscribed, velocity, pose, dt, layer, r_bm_off, bm_nblk, t_off, el_pose,
               el_stack, el_zadd, r_blk_off, r_blocks, rows, blk_radius, ppm, rc_start, rc_len,
               rc_x, rc_y, rx0, ry0, nrx, nry, reg_dyn, reg_dyncount, dyn_head, free_state,
               page_free, sides, side_len, rest, head, marked, pinned):
    """Splits a step's moves in two sides moved at once (Motion._move_apart): the robots
    whose moves draw (_draws), each with the regions its move may touch, on two sides of a
    line of regions (_sides; of the lines across x and across y at a few quantiles of the
    robots' places, the one that leaves the least to do: the larger side's blocks and the
    rest's), the rest to be moved after the sides, in order. Moves of robots that share no
    region commute (each reads and writes only the cells of its regions; a block's entries
    are its own, grid.entry_of), so this gives World._move's grid, poses and stalls. The
    sides' regions get a page each and a count that keeps it through the sides' moves
    (pinned: their list, up to a -1; undo with unpin). head (-1) and marked (False): a value
    per region of the table, left so. Returns the robots in rest (robots of `rest`, in
    order), -1 when a move may leave the table or no split halves the work (then nothing is
    done: move them in turn), or -2 - pages when the pool needs that many more pages."""
    n = pose.shape[0]
    cells = np.zeros((n, 4), np.int64)
    boxes = np.zeros((n, 4), np.int64)
    draws = np.zeros(n, np.bool_)
    weight = np.zeros(n, np.int64)
    ends = np.empty((2, n), np.int64)
    m = 0
    total = 0
    area = 0
    for i in range(n):
        if _draws(i, subscribed, velocity, r_blk_off):
            _cell_box(i, pose, velocity, dt, layer, r_bm_off, bm_nblk, t_off, el_pose,
                      el_stack, el_zadd, r_blk_off, r_blocks, rows, blk_radius, ppm, rc_start,
                      rc_len, rc_x, rc_y, cells[i])
            for k in range(4):
                boxes[i, k] = cells[i, k] >> grid.RBITS
            if (boxes[i, 0] < rx0 or boxes[i, 1] < ry0 or boxes[i, 2] >= rx0 + nrx
                    or boxes[i, 3] >= ry0 + nry):
                return -1
            draws[i] = True
            weight[i] = r_blk_off[i + 1] - r_blk_off[i]
            total += weight[i]
            area += (boxes[i, 2] - boxes[i, 0] + 1) * (boxes[i, 3] - boxes[i, 1] + 1)
            ends[0, m] = boxes[i, 2]
            ends[1, m] = boxes[i, 3]
            m += 1
    if m < 2:
        return -1
    entry_robot = np.empty(area, np.int64)
    entry_next = np.empty(area, np.int64)
    touched = np.empty(area, np.int64)
    side = np.empty(n, np.int64)
    best = total
    best_axis = best_split = -1
    ordered = np.empty((2, m), np.int64)
    ordered[0] = np.sort(ends[0, :m])
    ordered[1] = np.sort(ends[1, :m])
    for q in (5, 4, 6, 3, 7):     # past the median robot across x and y, then other tenths
        for axis in range(2):
            split = ordered[axis, m * q // 10] + 1
            w0, w1, w2 = _sides(cells, boxes, draws, weight, axis, split, head, entry_robot,
                                entry_next, touched, rx0, ry0, nrx, side)
            cost = max(w0, w1) + w2
            if cost < best:
                best, best_axis, best_split = cost, axis, split
        if 20 * best <= 11 * total:       # within a tenth of halving it: good enough
            break
    if 10 * best > 7 * total:      # not worth two threads
        return -1
    _sides(cells, boxes, draws, weight, best_axis, best_split, head, entry_robot, entry_next,
           touched, rx0, ry0, nrx, side)
    count = 0
    missing = 0
    for i in range(n):
        if side[i] < 2:
            for ty in range(boxes[i, 1] - ry0, boxes[i, 3] - ry0 + 1):
                for tx in range(boxes[i, 0] - rx0, boxes[i, 2] - rx0 + 1):
                    reg = ty * nrx + tx
                    if not marked[reg]:
                        marked[reg] = True
                        pinned[count] = reg
                        count += 1
                        if reg_dyn[reg] < 0:
                            missing += 1
    for j in range(count):
        marked[pinned[j]] = False
    if missing > free_state[0]:
        return -2 - (missing - free_state[0])
    for j in range(count):
        grid.hold_page(pinned[j], reg_dyn, dyn_head, free_state, page_free)
        reg_dyncount[pinned[j]] += 1
    pinned[count] = -1
    side_len[0] = side_len[1] = 0
    k = 0
    for i in range(n):
        t = side[i]
        if t < 2:
            sides[t, side_len[t]] = i
            side_len[t] += 1
        else:
            rest[k] = i
            k += 1
    return k


@kernel
def unpin(pinned, reg_dyn, reg_dyncount, free_state, page_free):
    """plan_apart's counts off its regions (pinned, up to a -1); a region left without an
    entry gives its page back, as UnMap does."""
    for j in range(pinned.shape[0]):
        reg = pinned[j]
        if reg < 0:
            return
        reg_dyncount[reg] -= 1
        if reg_dyncount[reg] == 0:
            page_free[free_state[0]] = reg_dyn[reg]
            free_state[0] += 1
            reg_dyn[reg] = -1


def elements(model, tails=()):
    """The chain elements (pose, stack, height) from the model's root's pose to the
    model's global pose (Model::GetGlobalPose), then `tails` added plainly."""
    path = []
    m = model
    while m.parent is not None:
        path.append(m)
        m = m.parent
    out = [(tuple(c.pose), bool(c.parent.stack_children), float(c.parent.geom_size[2]))
           for c in reversed(path)]
    return out + [(tuple(t), False, 0.0) for t in tails]


class Chains:
    """Targets (a robot slot and its chain elements each) as the kernels' tables."""

    def __init__(self, targets, shared=None):
        """targets: [(robot slot, elements())]; shared: per target, None or (a number, how
        many of its first elements it shares with the other targets of that number)."""
        counts = [len(els) for _, els in targets]
        flat = [e for _, els in targets for e in els]
        shared = shared or [None] * len(targets)
        self.shared = np.array([-1 if s is None else s[0] for s in shared], np.int64)
        self.prefix = np.array([0 if s is None else s[1] for s in shared], np.int64)
        self.robot = np.array([r for r, _ in targets], np.int64)
        self.off = np.concatenate(([0], np.cumsum(counts))).astype(np.int64)
        self.pose = np.array([e[0] for e in flat], np.float64).reshape(-1, 4)
        self.stack = np.array([e[1] for e in flat], np.bool_)
        self.zadd = np.array([e[2] for e in flat], np.float64)

    def poses(self, targets, robot_pose, out):
        """out[i] := the world pose of target targets[i] at the robots' poses now."""
        chain_poses(targets, self.robot, self.off, self.shared, self.prefix, self.pose,
                    self.stack, self.zadd, robot_pose, out)


class Motion:
    """The robots' tables for the kernels: bodies (per robot, its models with blocks, in
    drawing order: their chains to their body frames) and the position models' constants."""

    def __init__(self, robots, space):
        self.space = space
        bodies = []
        r_bm = [0]
        nblk = []
        for r in robots:
            for m, ks in r.blocks:
                bodies.append((r.index, elements(m, [m.geom_pose])))
                nblk.append(len(ks))
            r_bm.append(len(bodies))
        self.bodies = Chains(bodies)
        self.r_bm_off = np.array(r_bm, np.int64)
        self.bm_nblk = np.array(nblk, np.int64)
        sizes = [len(r.block_ids) for r in robots]
        self.r_blk_off = np.concatenate(([0], np.cumsum(sizes))).astype(np.int64)
        self.r_blocks = (np.concatenate([r.block_ids for r in robots]).astype(np.int64)
                         if robots else np.zeros(0, np.int64))
        most = max(sizes, default=0) or 1
        # scratch of the moves: a row per side moved at once (the first for the others)
        self.new_rows = np.zeros((2, most, 4))
        self.old_rows = np.zeros((2, most, 4))
        self.seqs = np.zeros((2, 2, most), np.int64)
        self.box = np.zeros((2, 4), np.int64)
        self.vx = np.zeros((2,) + space._vx.shape, np.int64)
        self.vy = np.zeros((2,) + space._vy.shape, np.int64)
        n = len(robots)
        self.bases = np.zeros(n, np.int64)
        self.in_order = np.arange(n, dtype=np.int64)
        self.sides = np.zeros((2, n), np.int64)
        self.side_len = np.zeros(2, np.int64)
        self.rest = np.zeros(n, np.int64)
        # move_work's most (every robot moving, its outlines as long as they can be): a
        # world of a few robots never plans
        caps = np.diff(np.append(space.rc_start, space.rc_x.shape[1] - 1))
        self._most_work = MOVE_CELLS * n + int(caps[self.r_blocks].sum())
        # plan_apart's per region of the grid's table (made at the first plan, and again
        # when the table grows)
        self._region_head = self._region_marked = self._pinned = np.zeros(0, np.int64)
        self._side_thread = None        # the second side's (made at the first split)
        ms = [r.model for r in robots]
        self.drive = np.array([DRIVES[m.drive] for m in ms], np.int64)
        self.wheelbase = np.array([m.wheelbase for m in ms], np.float64)
        self.vbounds = np.array([m.velocity_bounds for m in ms], np.float64).reshape(-1, 4, 2)
        self.abounds = np.array([m.acceleration_bounds for m in ms],
                                np.float64).reshape(-1, 4, 2)
        self.gps = np.array([m.localization == 'gps' for m in ms], np.bool_)
        self.error = np.array([m.integration_error for m in ms], np.float64).reshape(-1, 4)
        # the robots under position control, their velocity from Robot.commanded_velocity
        self.given = np.zeros(len(robots), np.bool_)
        self.given_velocity = np.zeros((len(robots), 4))

    def update(self, robots, state, due, subscribed, dt):
        """ModelPosition::Update of the robot slots `due` (int64 array)."""
        given = self.given
        positioned = np.flatnonzero(state.mode[due] > ACCELERATION).tolist()
        for i in positioned:
            slot = int(due[i])
            if subscribed[slot]:
                given[slot] = True
                self.given_velocity[slot] = robots[slot].commanded_velocity(dt)
        update_positions(due, subscribed, state.goal, state.mode, state.velocity, state.est,
                         state.pose, self.drive, self.wheelbase, self.vbounds, self.abounds,
                         self.gps, self.error, given, self.given_velocity, dt)
        if positioned:
            given[:] = False

    def move(self, state, subscribed, dt, layer):
        """Every subscribed robot's move, in order, and every robot's twist; with enough
        work, the robots far apart on two threads at once first (plan_apart)."""
        sp = self.space
        sp.seq = seq_bases(subscribed, state.velocity, self.r_bm_off, self.r_blk_off, sp.seq,
                           self.bases)
        order = self.in_order
        if (self._most_work >= APART_CELLS and numba_threads() > 1
                and move_work(subscribed, state.velocity, self.r_blk_off, self.r_blocks,
                              sp.rc_len, layer) >= APART_CELLS):
            order = self._move_apart(state, subscribed, dt, layer)
        first = 0
        while True:
            first = move_robots(
                order, first, True, self.bases, subscribed, state.velocity, state.pose,
                state.stalled, state.twist, dt, layer, *self._tables(), self.new_rows[0],
                self.old_rows[0], self.seqs[0], self.box[0], *self._grid(), self.vx[0],
                self.vy[0], *self._cells())
            if first < 0:
                return
            i = order[first]
            if sp.pages_short(self.r_blocks[self.r_blk_off[i]:self.r_blk_off[i + 1]]):
                sp.grow_pages()
            else:
                sp.resize(*self.box[0].tolist())

    def _move_apart(self, state, subscribed, dt, layer):
        """plan_apart's two sides moved at once, one in a thread of its own; the robots
        left to move in turn, in order."""
        sp = self.space
        tables = self._tables()
        regions = sp.nrx * sp.nry
        if self._region_head.size != regions:       # the table was made or has grown
            self._region_head = np.full(regions, -1, np.int64)
            self._region_marked = np.zeros(regions, np.bool_)
            self._pinned = np.empty(regions + 1, np.int64)
        pinned = self._pinned
        while True:
            k = plan_apart(subscribed, state.velocity, state.pose, dt, layer, *tables,
                           self.new_rows[0], sp.blk_radius, sp.ppm, sp.rc_start, sp.rc_len,
                           sp.rc_x, sp.rc_y, sp.rx0, sp.ry0, sp.nrx, sp.nry, sp.reg_dyn,
                           sp.reg_dyncount, sp.dyn_head, sp.free_state, sp.page_free,
                           self.sides, self.side_len, self.rest, self._region_head,
                           self._region_marked, pinned)
            if k >= -1:
                break
            sp.grow_pages(-2 - k)
        if k == -1:
            return self.in_order

        def move_side(t):
            move_robots(self.sides[t, :self.side_len[t]], 0, False, self.bases, subscribed,
                        state.velocity, state.pose, state.stalled, state.twist, dt, layer,
                        *tables, self.new_rows[t], self.old_rows[t], self.seqs[t], self.box[t],
                        *self._grid(), self.vx[t], self.vy[t], *self._cells())
        if self._side_thread is None:
            self._side_thread = ThreadPoolExecutor(1, thread_name_prefix='stage_moves')
        # the thread starts some 70 us late (its wake-up): it takes the side with fewer
        # robots (the sides commute, so either may run anywhere)
        small = 0 if self.side_len[0] < self.side_len[1] else 1
        other = self._side_thread.submit(move_side, small)
        move_side(1 - small)
        other.result()
        unpin(pinned, sp.reg_dyn, sp.reg_dyncount, sp.free_state, sp.page_free)
        return self.rest[:k]

    def _tables(self):
        """The robots' bodies and blocks, as the move kernels take them."""
        b = self.bodies
        return (self.r_bm_off, self.bm_nblk, b.off, b.pose, b.stack, b.zadd, self.r_blk_off,
                self.r_blocks)

    def _grid(self):
        sp = self.space
        return sp.blk_radius, sp.blk_pages, sp.ppm, sp.blk_pts, sp.blk_pts_off

    def _cells(self):
        sp = self.space
        return (sp.rc_start, sp.rc_len, sp.rc_x, sp.rc_y, sp.rx0, sp.ry0, sp.nrx, sp.nry,
                sp.reg_count, sp.reg_static, sp.reg_dyn, sp.reg_dyncount, sp.st_coll,
                sp.blk_class, sp.dyn_head, sp.ent_block, sp.ent_next, sp.ent_prev, sp.ent_seq,
                sp.free_state, sp.page_free, sp.blk_model, sp.blk_zmin, sp.blk_zmax,
                sp.model_root, sp.model_obstacle)
