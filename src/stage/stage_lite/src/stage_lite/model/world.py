"""The simulated world as Stage 4.3 and stageros 1.8.0 run it (no rospy).

Loading (World::Load and its post-load hook) is world_load's; the World runs what it loaded:
the commands, the step, reset, the rays, and the floor for pictures and maps.

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

from . import floor, grid, world_load
from .camera import CameraRig
from .pose import pose_add, stage_normalize
from .ranger import Ranger
from .robot import body_row
from .worldfile import WorldError

__all__ = ['World', 'WorldError', 'load_world']


class World:
    """A loaded world. Use load_world()."""

    def __init__(self, path, seed=None):
        self.path = path
        # one generator for what loading draws (random colours, odometry errors), then noise
        self._rng = np.random.default_rng(seed)
        loaded = world_load.load(path, self._rng)
        self.resolution_m = loaded.resolution_m
        self.ppm = loaded.ppm
        self.interval_us = loaded.interval_us
        self.interval_sim_s = self.interval_us / 1e6
        self.quit_time_s = loaded.quit_time_s
        self.speedup = loaded.speedup
        self.window = loaded.window
        self.models = loaded.models
        self.robots = loaded.robots
        self.space = loaded.space
        self.warnings = loaded.warnings
        self._ray_zs = loaded.ray_zs
        self._statics = loaded.statics
        self._static_cells = loaded.static_cells
        self._occupancy = None
        self.sim_time_us = 0
        self.updates = 0
        self._prepare_rays()
        # the cameras stageros publishes (camera.py); they draw before the step's moves
        self.cameras = CameraRig(self.models, self.robots, self._statics, self.ppm,
                                 self.window, self.warnings)

    # ---- the interface -------------------------------------------------------------------
    def set_command(self, i, vx, vy, wz):
        """stageros's cmdvelReceived: SetSpeed(x, y, a), applied at the robot's next update.
        Raises ValueError on NaN or infinity (the node refuses those with a WARN)."""
        vx, vy, wz = (finite_float(name, v)
                      for name, v in (('linear.x', vx), ('linear.y', vy), ('angular.z', wz)))
        self.robots[i].goal = (vx, vy, 0.0, wz)

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
        self.cameras.update(now)
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
    def _prepare_rays(self):
        """Every ranger of every robot, in order, and their tables for a step's cast."""
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


def finite_float(name, value):
    """value as a float; ValueError ('NAME must be finite, got VALUE') for NaN or infinity.

    The model's one finite check: the model depends on no package of the workspace (numpy,
    numba and Pillow only), so that Stage's rules stand alone and run from this source
    folder (the model-only bench's children import nothing else); the node and the view
    check through course_common.finite."""
    if not math.isfinite(value):
        raise ValueError('%s must be finite, got %r' % (name, value))
    return float(value)


def load_world(path, seed=None):
    """Parses the world file (includes, bitmaps) into a World; raises WorldError."""
    if not os.path.isfile(path):
        raise WorldError(path, None, 'the world file does not exist')
    return World(path, seed)
