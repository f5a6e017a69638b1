"""The simulated world as Stage 4.3 and stageros 1.8.0 run it (no rospy).

Loading (World::Load): every entity in file order becomes a model (a `block( )` joins its
model's body, a `sensor( )` its ranger, `window( )` is the GUI's), then every model's body is
sized and drawn into the grid in both layers.

One step (World::Update, as stageros drives it), sim time first advanced by interval_sim:
1. each position model due (every update_interval) turns its goal (the last cmd_vel) into
   its velocity: clamped to velocity_bounds, `car` steering converted; and updates its
   estimate: the world pose before this step's move (`gps`), or the velocity integrated
   with its odom_error (`odom`, from 0 0 0);
2. each position model, in file order, moves by velocity * interval (the translation turned
   by the OLD heading); its body is drawn into layer (updates % 2) at the new pose; if it
   then overlaps an obstacle of another model in that layer whose height range meets its
   own, the move is undone and the robot is stalled;
3. each ranger due casts its rays from its robot's pose after the move, through layer
   ((updates + 1) % 2): the bodies as drawn in the previous step
   (STAGE_RAYS_READ_LAST_LAYER; in Stage the rangers run in a worker thread beside the moves);
4. stageros publishes: odom = the estimate and the velocity, ground truth = the world pose.
"""
import math
import os

import numpy as np

from . import floor, grid
from .models import BUILTIN_TYPES, SIMULATED_TYPES, Position, Ranger, calc_size, new_model
from .pose import pose_add, stage_normalize
from .space import DynamicBlock, Space
from .worldfile import WorldError, Worldfile

__all__ = ['World', 'Robot', 'WorldError', 'load_world']

#: Top-level properties Stage reads (the GUI ones too: the window is optional here).
TOP_LEVEL = ('name', 'show_clock', 'show_clock_interval', 'threads', 'paused',
             'confirm_on_quit', 'log')


class RangerView:
    """What stageros publishes of a ranger: its first sensor's scan and the tf pose."""

    def __init__(self, model, sensor, robot_height):
        self.model = model
        self.sensor = sensor
        x, y, z, a = model.pose
        self.pose = (x, y, robot_height + z, a)       # base_link -> base_laser_link
        self.range_min, self.range_max = sensor.range
        self.samples = sensor.samples
        self.fov_rad = sensor.fov
        self.noise = sensor.noise
        self.ranges = np.full(self.samples, self.range_max, np.float32)
        self.intensities = np.zeros(self.samples, np.float32)
        self.has_data = False       # stageros publishes a ranger after its first update
        self.next_update_us = model.interval_us
        self.beam_z = model.ray_origin(sensor)[2]

    @property
    def angle_min(self):
        return -self.fov_rad / 2.0

    @property
    def angle_max(self):
        return self.fov_rad / 2.0

    @property
    def angle_increment(self):
        # stageros divides by samples - 1 even when it is 0 (IEEE: inf, or nan for fov 0)
        if self.samples > 1:
            return self.fov_rad / (self.samples - 1)
        return math.inf if self.fov_rad > 0 else math.nan

    def local_angles(self):
        """The beams' angles in the sensor's frame (a one-beam sensor's: angle_min)."""
        step = self.fov_rad / (self.samples - 1) if self.samples > 1 else 0.0
        return self.angle_min + np.arange(self.samples) * step


class Robot:
    """A position model and its Stage state (goal, velocity, estimate, stall)."""

    def __init__(self, index, model, rangers):
        self.index = index
        self.model = model
        self.model_name = model.name
        self.color_rgb = model.color[:3]
        self.size = model.geom_size
        self.origin = model.geom_pose
        self.rangers = rangers
        self.drive = model.drive
        self.localization = model.localization
        gp = model.global_pose()
        self.initial_global = gp
        self.start_pose = (gp[0], gp[1], gp[3])
        self.goal = (0.0, 0.0, 0.0, 0.0)
        self.velocity = model.initial_velocity
        self.est_pose = model.initial_estimate()
        self.stalled = False
        self.truth_twist = (0.0, 0.0, 0.0)
        self.next_update_us = model.interval_us
        self.tree = []          # every model of the robot (itself first), in drawing order
        self.blocks = []        # [(model, dynamic block indices)] in drawing order

    @property
    def pose(self):
        """(x, y, yaw): the world pose (ground truth)."""
        x, y, _, a = self.model.global_pose()
        return (x, y, a)

    @property
    def odom_pose(self):
        x, y, _, a = self.est_pose
        return (x, y, a)

    @property
    def command(self):
        """The velocity Stage applies (odom's twist): vx, vy, wz."""
        return (self.velocity[0], self.velocity[1], self.velocity[3])


class World:
    """A loaded world. Use load_world()."""

    def __init__(self, path, seed=None):
        self.path = path
        self._rng = np.random.default_rng(seed)
        wf = Worldfile(path)
        self.wf = wf
        self.resolution_m = wf.read_float(0, 'resolution', 0.02)
        if not self.resolution_m > 0:
            raise _top_error(wf, 'resolution', 'resolution must be > 0 m')
        self.ppm = 1.0 / self.resolution_m
        self.interval_us = int(1e3 * wf.read_float(0, 'interval_sim', 100.0))
        if self.interval_us <= 0:
            raise _top_error(wf, 'interval_sim', 'interval_sim must be at least 0.001 ms')
        self.interval_sim_s = self.interval_us / 1e6
        self.quit_time_s = int(1e6 * wf.read_float(0, 'quit_time', 0.0)) / 1e6
        self.speedup = wf.read_float(0, 'speedup', 1.0)
        for name in TOP_LEVEL:
            if wf.exists(0, name):
                wf.read_string(0, name, '')
        self.window = None
        self.sim_time_us = 0
        self.updates = 0
        self.models = []
        self._load_models(wf)
        self._setup()
        self.warnings = wf.warnings + wf.unused_warnings()

    @property
    def sim_time_s(self):
        return self.sim_time_us / 1e6

    # ---- loading ---------------------------------------------------------------------------
    def _load_models(self, wf):
        world_dir = os.path.dirname(os.path.abspath(self.path))
        by_entity = {}
        counts = {}
        for ent in wf.entities[1:]:
            parent = by_entity.get(ent.parent)
            if ent.kind == 'window':
                self.window = self._read_window(wf, ent.index)
            elif ent.kind == 'block':
                if parent is None:
                    raise WorldError(ent.path, ent.line, 'block( ) belongs inside a model')
                parent.load_block(wf, ent.index)
            elif ent.kind == 'sensor':
                if not isinstance(parent, Ranger):
                    raise WorldError(ent.path, ent.line, 'sensor( ) belongs inside a ranger')
                parent.load_sensor(wf, ent.index)
            elif ent.kind in BUILTIN_TYPES:
                if ent.parent != 0 and parent is None:
                    raise WorldError(ent.path, ent.line, 'a %s inside a window( )' % ent.kind)
                m = new_model(world_dir, parent, ent.kind, len(self.models), ent.index, counts)
                m.load(wf, self._rng)
                if ent.kind not in SIMULATED_TYPES:
                    wf.warnings.append('%s:%d: %s models are not simulated here; loaded as a'
                                       ' body' % (ent.path, ent.line, ent.kind))
                self.models.append(m)
                by_entity[ent.index] = m
            else:
                raise WorldError(ent.path, ent.line, 'unknown model type "%s" (Stage: "Model'
                                 ' type %s not found in model typetable")'
                                 % (ent.kind, ent.kind))

    @staticmethod
    def _read_window(wf, e):
        """The GUI's window( ) properties, read as numbers or strings."""
        out = {}
        for name in wf.entities[e].props:
            vals = wf.read_values(e, name)
            nums = []
            for v in vals:
                try:
                    nums.append(float(v))
                except ValueError:
                    nums = None
                    break
            vals = nums if nums is not None else vals
            out[name] = vals[0] if len(vals) == 1 else vals
        return out

    def _setup(self):
        """World::LoadWorldPostHook: size every body, draw everything; the robots."""
        for m in self.models:
            calc_size(m.blocks, m.geom_size)
        moving = set()
        self.robots = []
        for m in self.models:
            if isinstance(m, Position):
                moving.add(m.index)
                rangers = []
                for c in m.children:
                    if isinstance(c, Ranger):
                        if not c.sensors:
                            self.wf.warnings.append('%s: ranger %s has no sensor( ): not'
                                                    ' published' % (self.path, c.token))
                            continue
                        if len(c.sensors) > 1:
                            self.wf.warnings.append('%s: ranger %s has %d sensors; stageros'
                                                    ' publishes the first only'
                                                    % (self.path, c.token, len(c.sensors)))
                        rangers.append(RangerView(c, c.sensors[0], m.geom_size[2]))
                self.robots.append(Robot(len(self.robots), m, rangers))
            elif m.parent is not None and m.parent.index in moving:
                moving.add(m.index)
        roots = [m.root.index for m in self.models]
        self.space = Space(self.ppm, len(self.models), roots,
                           [m.ranger_return for m in self.models],
                           [m.obstacle_return for m in self.models])
        statics = ([], [], [], [], [])
        dynamic = []
        coll = []
        for m in self.models:
            for block in m.blocks:
                vx, vy = m.pixel_vertices(block, self.ppm)
                zmin, zmax = m.block_z(block)
                if m.index in moving:
                    d = DynamicBlock(m, block, zmin, zmax)
                    if (zmin, zmax) not in coll:
                        coll.append((zmin, zmax))
                    d.coll = coll.index((zmin, zmax))
                    d.vertices = (vx, vy)
                    dynamic.append(d)
                    continue
                n = grid.poly_cell_count(vx, vy)
                xs = np.empty(n, np.int64)
                ys = np.empty(n, np.int64)
                grid.poly_cells(vx, vy, xs, ys, 0)
                statics[0].append(xs)
                statics[1].append(ys)
                statics[2].append(np.full(n, m.index, np.int64))
                statics[3].append(np.full(n, zmin))
                statics[4].append(np.full(n, zmax))
        cells = tuple(np.concatenate(a) if a else np.zeros(0, t)
                      for a, t in zip(statics, (np.int64, np.int64, np.int64, float, float),
                                    strict=True))
        self._ray_zs = sorted({v.beam_z for r in self.robots for v in r.rangers})
        extent = self._extent(dynamic)
        self.space.build(cells, self._ray_zs, dynamic, coll, extent)
        self._static_cells = (cells[0].astype(np.int32), cells[1].astype(np.int32))
        self._statics = [m for m in self.models if m.index not in moving]
        self._occupancy = None
        index = {id(d): k for k, d in enumerate(dynamic)}
        for r in self.robots:
            r.tree = _tree(r.model)
            r.blocks = [(m, [index[id(d)] for d in dynamic if d.model is m]) for m in r.tree]
            r.blocks = [(m, ks) for m, ks in r.blocks if ks]
            r.block_ids = np.array([k for _, ks in r.blocks for k in ks], np.int64)
        self._dynamic = dynamic
        # load-time drawings in model order, both layers (sequence = the model's index)
        for r in self.robots:
            for m, ks in r.blocks:
                blocks = np.array(ks, np.int64)
                poses = np.repeat([body_row(m)], len(ks), axis=0)
                seqs = np.full(len(ks), m.index, np.int64)
                for layer in (0, 1):
                    self.space.draw(blocks, poses, layer, seqs)
        self._prepare_rays()

    @staticmethod
    def _extent(dynamic):
        if not dynamic:
            return (0, 0, 0, 0)
        xs = np.concatenate([d.vertices[0] for d in dynamic])
        ys = np.concatenate([d.vertices[1] for d in dynamic])
        return (int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max()))

    def _prepare_rays(self):
        views = [(r, v) for r in self.robots for v in r.rangers]
        self._views = views
        self._rays = self._ray_tables(range(len(views)))

    def _ray_tables(self, due):
        """The per-sensor tables of the rangers `due` (indices into _views) for Space.cast."""
        views = [self._views[k][1] for k in due]
        counts = np.array([v.samples for v in views], np.int64)
        return dict(
            offsets=np.concatenate(([0], np.cumsum(counts))).astype(np.int64),
            sensor=np.repeat(np.arange(len(views), dtype=np.int64), counts),
            incr=np.array([Ranger.sample_increment(v.sensor) for v in views], np.float64),
            rmax=np.array([v.range_max for v in views], np.float64),
            ray_class=np.array([self._ray_zs.index(v.beam_z) for v in views], np.int64),
            root=np.array([v.model.root.index for v in views], np.int64),
            origins=np.empty((len(views), 4), np.float64))

    # ---- the interface -------------------------------------------------------------------
    def set_command(self, i, vx, vy, wz):
        """stageros's cmdvelReceived: SetSpeed(x, y, a), applied at the robot's next update.
        Raises ValueError on NaN or infinity (the node refuses those with a WARN)."""
        for name, v in (('linear.x', vx), ('linear.y', vy), ('angular.z', wz)):
            if not math.isfinite(v):
                raise ValueError('%s must be finite, got %r' % (name, v))
        self.robots[i].goal = (float(vx), float(vy), 0.0, float(wz))

    def stop_all(self):
        """stageros's watchdog: SetSpeed(0, 0, 0) on every robot."""
        for r in self.robots:
            r.goal = (0.0, 0.0, 0.0, 0.0)

    def reset(self):
        """stageros's reset_positions: every robot back to its initial pose, stall cleared
        (goal, velocity and the odometry estimate are left as they are, as in Stage)."""
        for r in self.robots:
            if r.model.pose != r.initial_global:
                r.model.pose = r.initial_global
                poses = self._body_rows(r)
                for layer in (0, 1):
                    self.space.draw(r.block_ids, poses, layer, self._seqs(r))
            r.stalled = False

    def step(self):
        """One World::Update (see the module docstring)."""
        self.sim_time_us += self.interval_us
        now = self.sim_time_us
        dt = self.interval_us / 1e6
        for r in self.robots:
            if r.next_update_us <= now:
                self._update_position(r, dt)
                r.next_update_us = now + r.model.interval_us
        layer = self.updates % 2
        for r in self.robots:
            old = r.pose
            self._move(r, dt, layer)
            new = r.pose
            r.truth_twist = ((new[0] - old[0]) / dt, (new[1] - old[1]) / dt,
                             stage_normalize(new[2] - old[2]) / dt)
        self._cast_rays(now, (self.updates + 1) % 2)
        self.updates += 1

    # ---- Stage's position model ------------------------------------------------------------
    def _update_position(self, r, dt):
        """ModelPosition::Update in velocity mode."""
        m = r.model
        gx, gy, gz, ga = r.goal
        if m.drive == 'omni':
            vel = [gx, gy, 0.0, ga]
        elif m.drive == 'car':
            vel = [gx * math.cos(ga), 0.0, 0.0, gx * math.sin(ga) / m.wheelbase]
        else:
            vel = [gx, 0.0, 0.0, ga]
        for k, (lo, hi) in enumerate(m.velocity_bounds):
            vel[k] = lo if vel[k] < lo else (hi if vel[k] > hi else vel[k])
        r.velocity = tuple(vel)
        if m.localization == 'gps':
            r.est_pose = m.global_pose()
        else:
            ex, ey, _, ea = m.integration_error
            x, y, z, a = r.est_pose
            a = stage_normalize(a + (vel[3] * dt) * (1.0 + ea))
            cosa = math.cos(a)
            sina = math.sin(a)
            dx = (vel[0] * dt) * (1.0 + ex)
            dy = (vel[1] * dt) * (1.0 + ey)
            x += dx * cosa + dy * sina
            y -= dy * cosa - dx * sina      # Stage's sign, kept (STAGE_ODOM_Y_SIGN)
            r.est_pose = (x, y, z, a)

    def _move(self, r, dt, layer):
        """ModelPosition::Move: the provisional move, drawn in `layer`, undone on a
        collision."""
        vx, vy, vz, va = r.velocity
        if not (vx or vy or vz or va):
            return
        m = r.model
        start = m.pose
        old = self._body_rows(r)
        m.pose = pose_add(start, (vx * dt, vy * dt, vz * dt, stage_normalize(va * dt)))
        if not len(r.block_ids):
            r.stalled = False
            return
        new = self._body_rows(r)
        seqs = np.array([self._seqs(r), self._seqs(r)])
        if self.space.move(r.block_ids, new, old, seqs, layer) != grid.NO_HIT:
            m.pose = start
            r.stalled = True
        else:
            r.stalled = False

    @staticmethod
    def _body_rows(r):
        """Per block of the robot's tree: its model's body pose (x, y, cos, sin)."""
        return np.array([row for m, ks in r.blocks for row in [body_row(m)] * len(ks)])

    def _seqs(self, r):
        """Per block of the robot's tree: a new drawing number per model (MapWithChildren)."""
        return np.array([s for m, ks in r.blocks for s in [self.space.next_seq()] * len(ks)],
                        np.int64)

    # ---- rays --------------------------------------------------------------------------
    def _cast_rays(self, now, layer):
        due = []
        for k, (_, v) in enumerate(self._views):
            if v.next_update_us <= now:
                v.next_update_us = now + v.model.interval_us
                due.append(k)
        if due:
            self.cast_rays(due, layer)

    def cast_rays(self, due=None, layer=None):
        """Casts the rays of the rangers `due` (indices, default all) from the robots' poses
        now, through `layer` (default: the one the next step's rays read)."""
        if layer is None:
            layer = (self.updates + 1) % 2
        tables = self._rays if due is None or len(due) == len(self._views) \
            else self._ray_tables(due)
        due = range(len(self._views)) if due is None else due
        views = [self._views[k][1] for k in due]
        origins = tables['origins']
        for i, v in enumerate(views):
            origins[i] = v.model.ray_origin(v.sensor)
        rng, hit = self.space.cast(origins, tables['incr'], tables['offsets'], tables['sensor'],
                                   tables['rmax'], tables['ray_class'], tables['root'], layer)
        rr = self.space.model_rr
        intensities = np.where(hit >= 0, rr[np.maximum(hit, 0)], 0.0)
        off = tables['offsets']
        for i, v in enumerate(views):
            ranges = rng[off[i]:off[i + 1]]
            if any(v.noise):
                ranges = self._noisy(ranges, v)
            v.ranges[:] = ranges
            v.intensities[:] = intensities[off[i]:off[i + 1]]
            v.has_data = True

    def scan_from(self, view, pose):
        """The ranges (float32) `view` reads with its robot at `pose` (x, y, z, a), through
        the layer the last step's rays read. In Stage the rangers run in a worker thread
        beside the moves: now and then one starts before its robot has moved, and its scan
        is this one with the robot's pose before the step."""
        robot = view.model.parent
        keep = robot.pose
        robot.pose = pose
        try:
            tables = self._ray_tables([k for k, (_, v) in enumerate(self._views)
                                       if v is view])
            tables['origins'][0] = view.model.ray_origin(view.sensor)
        finally:
            robot.pose = keep
        rng, _ = self.space.cast(tables['origins'], tables['incr'], tables['offsets'],
                                 tables['sensor'], tables['rmax'], tables['ray_class'],
                                 tables['root'], self.updates % 2)
        return rng.astype(np.float32)

    def _noisy(self, ranges, v):
        """Stage's range noise: + range * proportional * U[-1, 1) + N(0, constant variance),
        on beams that hit (Stage's own random numbers cannot be reproduced)."""
        const, prop, _ = v.noise
        hit = ranges < v.range_max
        out = ranges.copy()
        n = int(hit.sum())
        out[hit] += (ranges[hit] * prop * self._rng.uniform(-1.0, 1.0, n)
                     + self._rng.normal(0.0, math.sqrt(max(const, 0.0)), n))
        return out

    # ---- pictures and maps ---------------------------------------------------------------
    def occupancy(self):
        """(grid bool [rows, cols] of the static bodies, filled, origin_x, origin_y,
        resolution_m); row 0 is the lowest y. Computed once."""
        if self._occupancy is None:
            self._occupancy = floor.filled(self._statics, self._static_cells,
                                           [r.start_pose[:2] for r in self.robots], self.ppm)
        return self._occupancy


def body_row(m):
    """The model's body pose as the grid kernels take it: (x, y, cos a, sin a)."""
    x, y, _, a = m.body_pose()
    return (x, y, math.cos(a), math.sin(a))


def _tree(model):
    out = [model]
    for c in model.children:
        out.extend(_tree(c))
    return out


def _top_error(wf, name, what):
    p = wf.prop(0, name)
    return WorldError(p.path if p else wf.path, p.line if p else None, what)


def load_world(path, seed=None):
    """Parses the world file (includes, bitmaps) into a World; raises WorldError."""
    if not os.path.isfile(path):
        raise WorldError(path, None, 'the world file does not exist')
    return World(path, seed)
