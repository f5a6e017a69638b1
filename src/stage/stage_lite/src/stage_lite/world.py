"""The simulated world: load a Stage world file, step it, read robots and scans (no rospy).

One step (Stage 4.3's order): sim time advances by interval_sim; every ranger is cast on the
poses of the previous step; every robot, in world-file order, makes its provisional
body-frame Euler move, which is undone whole (and the robot stalled) if its footprint then
overlaps a static obstacle or another body whose height range overlaps its own.
"""

import math
import os

import numpy as np

from . import bitmap, kinematics, models, worldfile
from .raycast import StaticField, ray_boxes
from .worldfile import WorldError

__all__ = ['World', 'Robot', 'WorldError', 'load_world']

TOP_LEVEL = ('threads', 'paused', 'show_clock', 'show_clock_interval', 'log', 'name')


class Robot:
    """A position model and its state (see the interface note for each attribute)."""

    def __init__(self, index, model, drive, localization, odom_error, bounds, rng):
        self.index = index
        self.model = model
        model.robot = self
        self.model_name = model.name
        self.color_rgb = model.color_rgb
        self.size = model.size
        self.origin = model.origin
        self.height_m = model.size[2]
        self.z_range = model.z_range
        self.drive = drive
        self.localization = localization
        self.velocity_bounds = bounds
        self.obstacle_return = model.obstacle_return
        self.ranger_return = model.ranger_return
        self.start_pose = (model.pose[0], model.pose[1], kinematics.normalize(model.pose[3]))
        # Stage draws the odometry error once, uniform in +-odom_error/2
        e = odom_error
        self.odom_error_drawn = tuple(float(rng.uniform(-v / 2, v / 2)) if v else 0.0
                                      for v in (e[0], e[1], e[3]))
        self.rangers = []
        self.half_diag = 0.5 * math.hypot(self.size[0], self.size[1]) + math.hypot(
            self.origin[0], self.origin[1])
        self.reset()

    def reset(self):
        self.pose = self.start_pose
        self.odom_pose = self.start_pose
        self.command = (0.0, 0.0, 0.0)
        self.truth_twist = (0.0, 0.0, 0.0)
        self.stalled = False

    def body(self, pose=None):
        """(cx, cy, yaw) of the body's box at `pose` (default the current one)."""
        o = self.origin
        return kinematics.body_pose(pose or self.pose, (o[0], o[1], o[3]))

    def corners(self, pose=None):
        cx, cy, a = self.body(pose)
        return kinematics.rect_corners(cx, cy, a, self.size[0], self.size[1])


class World:
    """A loaded world. Use load_world(); attributes as in the interface note."""

    def __init__(self, path, seed=0):
        self.path = path
        self.sim_time_s = 0.0
        self._rng = np.random.default_rng(seed)
        parsed = worldfile.parse(path)
        top = parsed.top
        self.warnings = []
        self.resolution_m = top.number('resolution', 0.02)
        self.interval_sim_s = top.number('interval_sim', 100.0) / 1000.0
        self.speedup = top.number('speedup', 1.0)
        self.quit_time_s = top.number('quit_time', 0.0)
        for k in TOP_LEVEL:
            top.prop(k)
        if not self.resolution_m > 0:
            raise top.error('resolution', 'resolution must be > 0 m')
        if not self.interval_sim_s > 0:
            raise top.error('interval_sim', 'interval_sim must be > 0 ms')
        if not (self.speedup > 0 or self.speedup == -1):
            raise top.error('speedup', 'speedup must be > 0, or -1 for as fast as possible')
        self.window = None
        if parsed.window is not None:
            parsed.window.use_all()
            self.window = {k: (p.values[0] if len(p.values) == 1 else list(p.values))
                           for k, p in parsed.window.props.items()}
        self.models = []
        self.robots = []
        self._statics = []
        base_dir = os.path.dirname(os.path.abspath(path))
        for ent in parsed.models:
            self._build(ent, None, None, base_dir)
        self._build_grid()
        self.warnings = self.warnings + parsed.unused_warnings()
        self._half_diags = np.array([r.half_diag for r in self.robots])
        self._prepare_rays()

    # ---- loading -------------------------------------------------------------------------
    def _build(self, ent, parent, robot, base_dir):
        kind = ent.kind
        if kind in ('window', 'sensor', 'block'):
            if kind == 'block':
                ent.use_all()
                self.warnings.append('%s:%d: block( ) geometry is not simulated; the model\'s'
                                     ' size box is used' % (ent.path, ent.line))
            return
        default = {'position': models.POSITION_SIZE, 'ranger': models.RANGER_SIZE}.get(
            kind, models.DEFAULT_SIZE)
        m = models._read_common(ent, parent, kind, self.warnings, default)
        if parent is not None:
            parent.children.append(m)
        self.models.append(m)
        if kind == 'position':
            if robot is not None:
                raise ent.error(None, 'a position model inside another is not supported')
            drive, loc, err, bounds = models.read_position(ent)
            sub = np.random.default_rng([int(self._rng.integers(1 << 31)), len(self.robots)])
            robot = Robot(len(self.robots), m, drive, loc, err, bounds, sub)
            self.robots.append(robot)
            ent.prop('bitmap')
            ent.prop('boundary')
        elif kind == 'ranger':
            if robot is None:
                self.warnings.append('%s:%d: a ranger outside a position model is not'
                                     ' published' % (ent.path, ent.line))
                for s in ent.children:
                    s.use_all()
            else:
                robot.rangers.append(models.read_ranger(ent, m, robot.height_m,
                                                        self.warnings))
        elif robot is None:
            m.boundary = ent.number('boundary', 0.0) != 0
            m.placement = models.read_placement(ent, m, base_dir)
            self._statics.append(m)
        else:
            ent.prop('bitmap')
            ent.prop('boundary')
        if kind not in ('model', 'position', 'ranger'):
            self.warnings.append('%s:%d: %s models are not simulated; loaded as a plain body'
                                 % (ent.path, ent.line, kind))
        for c in ent.children:
            self._build(c, m, robot, base_dir)

    def _build_grid(self):
        res = self.resolution_m
        pts = [m.placement.corners() for m in self._statics]
        pts += [np.array([r.start_pose[:2]]) for r in self.robots]
        pts = np.vstack(pts) if pts else np.zeros((1, 2))
        self.grid_spec = bitmap.GridSpec.covering(pts[:, 0].min(), pts[:, 1].min(),
                                                  pts[:, 0].max(), pts[:, 1].max(), res)
        self._masks = []
        for m in self._statics:
            self._masks.append(bitmap.rasterise(m.placement, self.grid_spec, m.boundary))
        self._fields = {}

    def _field(self, members):
        """The StaticField of a set of static models (cached), with per-cell model labels
        when more than one model is in it (for intensities)."""
        key = tuple(members)
        if key not in self._fields:
            occ = np.zeros((self.grid_spec.rows, self.grid_spec.cols), bool)
            labels = None
            if len(key) > 1:
                labels = np.zeros(occ.shape, np.uint8)
            for j, i in enumerate(key):
                occ |= self._masks[i]
                if labels is not None:
                    labels[self._masks[i]] = j
            f = StaticField(occ, self.grid_spec)
            f.labels = labels
            f.members = key
            self._fields[key] = f
        return self._fields[key]

    def _prepare_rays(self):
        """Groups every ranger by the static field its beam height sees and precomputes the
        concatenated per-beam tables of each group."""
        for r in self.robots:
            r.collision_field = self._field(
                [i for i, m in enumerate(self._statics)
                 if m.obstacle_return and kinematics.z_overlap(m.z_range, r.z_range)])
        groups = {}
        for r in self.robots:
            for g in r.rangers:
                vis = tuple(i for i, m in enumerate(self._statics) if m.ranger_return >= 0
                            and m.z_range[0] <= g.beam_z <= m.z_range[1])
                groups.setdefault(vis, []).append((r, g))
        self._ray_groups = []
        for vis, members in groups.items():
            field = self._field(list(vis))
            counts = [g.samples for _, g in members]
            local = np.concatenate([g.local_angles() for _, g in members])
            rmax = np.concatenate([np.full(g.samples, g.range_max) for _, g in members])
            # only a robot's heading changes: the beams' directions are rotations of these
            trig = (np.cos(local), np.sin(local))
            self._ray_groups.append((field, members, np.array(counts), local, rmax, trig))

    # ---- the interface -------------------------------------------------------------------
    def occupancy(self):
        """(grid bool [rows, cols] of static obstacles, origin_x, origin_y, resolution_m);
        row 0 is the lowest y."""
        f = self._field([i for i, m in enumerate(self._statics) if m.obstacle_return])
        s = self.grid_spec
        return f.occupied, s.origin_x, s.origin_y, s.resolution

    def set_command(self, i, vx, vy, wz):
        r = self.robots[i]
        r.command = kinematics.clamp_command(float(vx), float(vy), float(wz),
                                             r.velocity_bounds, r.drive)

    def stop(self, i):
        self.robots[i].command = (0.0, 0.0, 0.0)

    def stop_all(self):
        for r in self.robots:
            r.command = (0.0, 0.0, 0.0)

    def reset(self):
        for r in self.robots:
            r.reset()

    def step(self):
        self.sim_time_s += self.interval_sim_s
        self.cast_rays()
        dt = self.interval_sim_s
        for r in self.robots:
            old = r.pose
            self._move(r, dt)
            new = r.pose
            r.truth_twist = ((new[0] - old[0]) / dt, (new[1] - old[1]) / dt,
                             kinematics.normalize(new[2] - old[2]) / dt)
            if r.localization == 'odom':
                vx, vy, wz = r.command
                ex, ey, ea = r.odom_error_drawn
                r.odom_pose = kinematics.compose(
                    r.odom_pose, (vx * dt * (1 + ex), vy * dt * (1 + ey), wz * dt * (1 + ea)))
            else:
                r.odom_pose = r.pose

    def _move(self, r, dt):
        if r.command == (0.0, 0.0, 0.0):
            return
        new = kinematics.euler_step(r.pose, r.command, dt)
        if self.collides(r, new):
            r.stalled = True
        else:
            r.pose = new
            r.stalled = False

    def collides(self, r, pose):
        """True when robot r's footprint at `pose` overlaps a static obstacle, or comes within
        one grid cell of another body (Stage rasterises bodies on the grid, so bodies one
        cell apart already share a cell) while not moving away from it."""
        res = self.resolution_m
        cx, cy, a = r.body(pose)
        f = r.collision_field
        if f.members and f.clearance(cx, cy) <= r.half_diag + res:
            xs, ys = kinematics.rect_samples(cx, cy, a, r.size[0], r.size[1], res)
            if f.any_occupied(xs, ys):
                return True
        if not r.obstacle_return:
            return False
        mine = None
        # every other body's centre at once; only the near ones are looked at one by one
        xy = np.array([o.pose[:2] for o in self.robots])
        near = np.hypot(xy[:, 0] - pose[0], xy[:, 1] - pose[1]) <= (
            r.half_diag + self._half_diags + 2 * res)
        for j in np.flatnonzero(near):
            o = self.robots[j]
            if o is r or not o.obstacle_return or not kinematics.z_overlap(r.z_range,
                                                                           o.z_range):
                continue
            if mine is None:
                mine = r.corners(pose)
            theirs = o.corners()
            gap = kinematics.rect_gap(mine, theirs)
            if gap < res and gap < kinematics.rect_gap(r.corners(), theirs) + 1e-12:
                return True
        return False

    def cast_rays(self):
        """Fills every ranger's ranges and intensities from the current poses."""
        for field, members, counts, local, rmax, (cl, sl) in self._ray_groups:
            org = np.array([kinematics.compose(r.pose, (g.pose[0], g.pose[1], g.pose[3]))
                            for r, g in members])
            ox = np.repeat(org[:, 0], counts)
            oy = np.repeat(org[:, 1], counts)
            ang = np.repeat(org[:, 2], counts) + local
            noisy = [g for _, g in members if any(g.noise)]
            if noisy:
                ang = ang + self._angle_noise(members, counts)
                rng, cell = field.march(ox, oy, ang, rmax)
            else:
                cy = np.repeat(np.cos(org[:, 2]), counts)
                sy = np.repeat(np.sin(org[:, 2]), counts)
                rng, cell = field.march_dir(ox, oy, cy * cl - sy * sl, sy * cl + cy * sl, rmax)
            if field.labels is None:
                inten = np.where(np.isfinite(rng), self._statics[field.members[0]].ranger_return
                                 if field.members else 0.0, 0.0)
            else:
                lab = field.labels.ravel()[np.maximum(cell, 0)]
                rr = np.array([self._statics[i].ranger_return for i in field.members])
                inten = np.where(cell >= 0, rr[lab], 0.0)
            start = 0
            for (r, g), n in zip(members, counts, strict=True):
                sl = slice(start, start + n)
                start += n
                self._bodies(r, g, ox[sl][:1], oy[sl][:1], ang[sl], rng, inten, sl)
                gr = rng[sl]
                if any(g.noise):
                    hit = np.isfinite(gr)
                    sigma = g.noise[0] + g.noise[1] * gr[hit]
                    gr[hit] = np.maximum(0.0, gr[hit] + self._rng.normal(0.0, 1.0, hit.sum())
                                         * sigma)
                miss = ~np.isfinite(gr) | (gr > g.range_max)
                g.ranges[:] = np.where(miss, g.range_max, gr)
                g.intensities[:] = np.where(miss, 0.0, inten[sl])

    def _angle_noise(self, members, counts):
        sig = np.repeat([g.noise[2] for _, g in members], counts)
        return self._rng.normal(0.0, 1.0, sig.size) * sig

    def _bodies(self, r, g, ox, oy, ang, rng, inten, sl):
        """Other robots whose height range holds this ranger's beam, hit analytically."""
        boxes, rets = [], []
        for o in self.robots:
            if o is r or o.ranger_return < 0:
                continue
            if not o.z_range[0] <= g.beam_z <= o.z_range[1]:
                continue
            if math.hypot(o.pose[0] - ox[0], o.pose[1] - oy[0]) > g.range_max + o.half_diag:
                continue
            cx, cy, a = o.body()
            boxes.append((cx, cy, a, o.size[0] / 2, o.size[1] / 2))
            rets.append(o.ranger_return)
        if not boxes:
            return
        t, which = ray_boxes(ox[0], oy[0], ang, boxes)
        closer = t < rng[sl]
        idx = np.flatnonzero(closer) + sl.start
        rng[idx] = t[closer]
        inten[idx] = np.asarray(rets)[which[closer]]


def load_world(path, seed=0):
    """Parses the world file (includes, bitmaps) into a World; raises WorldError."""
    if not os.path.isfile(path):
        raise WorldError(path, None, 'the world file does not exist')
    return World(path, seed)
