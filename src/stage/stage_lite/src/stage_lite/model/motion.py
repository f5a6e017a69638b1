"""Every robot's update and move in one kernel each, Stage's rules in Stage's order (no rospy).

ModelPosition::Update (the goal turned into the velocity, the estimate) and
ModelPosition::Move (the move, drawn in the grid, undone on a collision) for all the robots
of a step, on the world's RobotArrays (robot_state.py), and the world poses of what the
robots carry (their bodies' frames, their sensors' first rays) from the robots' poses.
Each is the World's per-robot Python (world.py) operation for operation: pose sums in
Stage's order (pose.py), cos and sin from the same C library, so every double is the same.
The World uses them when every robot is a top-level model (its pose is its world pose);
a robot on another model moves the World's own way.
"""
import math

import numpy as np

from . import grid
from .jit import njit
from .robot_state import MODE_CODE

VELOCITY = MODE_CODE['velocity']
ACCELERATION = MODE_CODE['acceleration']
DIFF, OMNI, CAR = 0, 1, 2
DRIVES = {'diff': DIFF, 'omni': OMNI, 'car': CAR}


@njit(cache=True)
def normalize(a):
    """pose.stage_normalize."""
    while a < -math.pi:
        a += 2.0 * math.pi
    while a > math.pi:
        a -= 2.0 * math.pi
    return a


@njit(cache=True)
def pose_add(px, py, pz, pa, qx, qy, qz, qa):
    """pose.pose_add."""
    return pose_add_turned(px, py, pz, pa, math.cos(pa), math.sin(pa), qx, qy, qz, qa)


@njit(cache=True)
def pose_add_turned(px, py, pz, pa, cosa, sina, qx, qy, qz, qa):
    """pose_add with cos(pa) and sin(pa) given (computed once for poses added to one)."""
    return (px + qx * cosa - qy * sina, py + qx * sina + qy * cosa, pz + qz,
            normalize(pa + qa))


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
def _clamp(v, lo, hi):
    return lo if v < lo else (hi if v > hi else v)


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
def move_robots(first, subscribed, velocity, pose, stalled, twist, dt, layer, r_bm_off,
                bm_nblk, t_off, el_pose, el_stack, el_zadd, r_blk_off, r_blocks, new_rows,
                old_rows, seqs, seq, box, blk_radius, blk_pages, ppm, pts, pts_off, vx, vy,
                rc_start, rc_len, rc_x, rc_y, rx0, ry0, nrx, nry, reg_count, reg_static,
                reg_dyn, reg_dyncount, st_coll, blk_class, dyn_head, ent_block, ent_next, ent_seq,
                free_state, ent_free, page_free, blk_model, blk_zmin, blk_zmax, model_root,
                model_obstacle):
    """World.step's moves from robot `first` on, in order (World._move of each subscribed
    robot, then its ground truth's twist). Returns -1 when done, or the robot whose move
    needs more free pages (Space.pages_short) or a larger region table (box: the cells it
    must hold); nothing of its move done yet."""
    for i in range(first, pose.shape[0]):
        ox, oy, oa = pose[i, 0], pose[i, 1], pose[i, 3]
        vxs, vys, vzs, vas = velocity[i, 0], velocity[i, 1], velocity[i, 2], velocity[i, 3]
        if subscribed[i] and (vxs != 0.0 or vys != 0.0 or vzs != 0.0 or vas != 0.0):
            sx, sy, sz, sa = pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3]
            b0 = r_blk_off[i]
            nb = r_blk_off[i + 1] - b0
            _body_rows(i, pose, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd,
                       old_rows)
            nx, ny, nz, na = pose_add(sx, sy, sz, sa, vxs * dt, vys * dt, vzs * dt,
                                      normalize(vas * dt))
            pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = nx, ny, nz, na
            if nb == 0:
                stalled[i] = False
            else:
                _body_rows(i, pose, r_bm_off, bm_nblk, t_off, el_pose, el_stack, el_zadd,
                           new_rows)
                blocks = r_blocks[b0:b0 + nb]
                need = 0
                for k in range(nb):
                    need += blk_pages[blocks[k]]
                if need > free_state[0]:
                    pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = sx, sy, sz, sa
                    return i
                if _outside(new_rows, nb, blocks, blk_radius, ppm, rx0, ry0, nrx, nry, box):
                    pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = sx, sy, sz, sa
                    return i
                for row in range(2):
                    n = 0
                    for b in range(r_bm_off[i], r_bm_off[i + 1]):
                        seq[0] += 1
                        for _k in range(bm_nblk[b]):
                            seqs[row, n] = seq[0]
                            n += 1
                hit = grid.move(blocks, new_rows[:nb], old_rows[:nb], seqs[:, :nb], layer,
                                ppm, pts, pts_off, vx, vy, rc_start, rc_len, rc_x, rc_y, rx0,
                                ry0, nrx, nry, reg_count, reg_static, reg_dyn, reg_dyncount,
                                st_coll, blk_class, dyn_head, ent_block, ent_next, ent_seq,
                                free_state, ent_free, page_free, blk_model, blk_zmin,
                                blk_zmax, model_root, model_obstacle)
                if hit != grid.NO_HIT:
                    pose[i, 0], pose[i, 1], pose[i, 2], pose[i, 3] = sx, sy, sz, sa
                    stalled[i] = True
                else:
                    stalled[i] = False
        twist[i, 0] = (pose[i, 0] - ox) / dt
        twist[i, 1] = (pose[i, 1] - oy) / dt
        twist[i, 2] = normalize(pose[i, 3] - oa) / dt
    return -1


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
        self.new_rows = np.zeros((most, 4))
        self.old_rows = np.zeros((most, 4))
        self.seqs = np.zeros((2, most), np.int64)
        self.box = np.zeros(4, np.int64)
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
        """Every subscribed robot's move, in order, and every robot's twist."""
        sp = self.space
        first = 0
        while True:
            seq = np.array([sp.seq], np.int64)
            first = move_robots(
                first, subscribed, state.velocity, state.pose, state.stalled, state.twist,
                dt, layer, self.r_bm_off, self.bm_nblk, self.bodies.off, self.bodies.pose,
                self.bodies.stack, self.bodies.zadd, self.r_blk_off, self.r_blocks,
                self.new_rows, self.old_rows, self.seqs, seq, self.box, sp.blk_radius,
                sp.blk_pages, sp.ppm,
                sp.blk_pts, sp.blk_pts_off, sp._vx, sp._vy, sp.rc_start, sp.rc_len, sp.rc_x,
                sp.rc_y, sp.rx0, sp.ry0, sp.nrx, sp.nry, sp.reg_count, sp.reg_static,
                sp.reg_dyn, sp.reg_dyncount, sp.st_coll, sp.blk_class, sp.dyn_head,
                sp.ent_block, sp.ent_next, sp.ent_seq, sp.free_state, sp.ent_free,
                sp.page_free, sp.blk_model, sp.blk_zmin, sp.blk_zmax, sp.model_root,
                sp.model_obstacle)
            sp.seq = int(seq[0])
            if first < 0:
                return
            blocks = self.r_blocks[self.r_blk_off[first]:self.r_blk_off[first + 1]]
            if sp.pages_short(blocks):
                sp.grow_pages()
            else:
                sp.resize(*self.box.tolist())
