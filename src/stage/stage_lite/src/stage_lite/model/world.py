"""The simulated world as Stage 4.3 and stageros 1.8.0 run it (no rospy).

Loading (World::Load and its post-load hook) is world_load's; the controllers named by the
models' `ctrl` are started by controllers.py (their Init, in model order); the World runs
what it loaded: the subscriptions, the commands, the step, reset, the rays, and the floor for
pictures and maps.

A model updates only while subscribed (scheduler.py): stageros subscribes every robot and the
rangers it carries (World(stageros=True), the default), Stage's own `stage` program nothing
but what the controllers subscribe. One step (World::Update), sim time first advanced by
interval_sim:
1. queue 0's due models, in the order Stage's event queue gives them (a blobfinder scans;
   fiducial.py, blobfinder.py): each position model turns its goal (the last cmd_vel or
   controller command) into its velocity (velocity, acceleration or position control;
   clamped to velocity_bounds, `car` steering converted) and updates its estimate: the
   world pose before this step's move (`gps`), or the velocity integrated with its
   odom_error (`odom`, from 0 0 0);
2. each subscribed position model, in file order, moves by velocity * interval (the
   translation turned by the OLD heading); its body is drawn into layer (updates % 2) at the
   new pose; if it then overlaps an obstacle of another model in that layer whose height
   range meets its own, the move is undone and the robot is stalled;
3. the workers' due models, queue by queue: each ranger casts every sensor's rays from its
   robot's pose after the move, through layer ((updates + 1) % 2): the bodies as drawn in
   the previous step (STAGE_RAYS_READ_LAST_LAYER; in Stage the rangers run in worker threads
   beside the moves), then draws its noise from random() beam by beam (noise.py); each
   fiducial finder looks for the fiducial-bearing models around it;
4. the update callbacks of every model that updated (the controllers), queue by queue, then
   the world's callbacks, then the energy model's charge update (energy.py);
5. stageros publishes: odom = the estimate and the velocity, ground truth = the world pose.
"""
import math
import os

import numpy as np

from . import controllers, floor, grid, world_load
from .blobfinder import Blobfinder
from .camera import CameraRig
from .energy import Energy
from .fiducial import Fiducial, FiducialIndex
from .glibc_random import Rand48, Random
from .noise import RangerNoise
from .pose import pose_add, stage_normalize
from .ranger import Ranger
from .robot import body_row
from .scheduler import CB_UPDATE, Scheduler
from .sight import Sight
from .stage_api import api_of
from .worldfile import WorldError

__all__ = ['World', 'WorldError', 'load_world']


class World:
    """A loaded world. Use load_world()."""

    def __init__(self, path, seed=None, stageros=True, ctrlargs='', model_order=None):
        """seed: random()'s srandom and drand48's srand48 (default: an unseeded process's,
        srandom(1) and glibc's zero drand48 state), and the load-time draws' generator;
        stageros: subscribe every robot and its rangers as stageros does (else only what
        the controllers subscribe, as Stage's `stage`); ctrlargs: `stage -a`'s argument
        string, World::ctrlargs, given to every controller; model_order: the models'
        tokens in the order of Stage's World::models, a set of pointers ordered by the
        models' addresses in memory (STAGE_MODEL_POINTER_ORDER): the order Stage starts the
        controllers, moves the robots and lists a finder's readings in. It follows nothing
        in the world (the same at every run of one program); without it, file order."""
        self.path = path
        # one generator for what loading draws (random colours, odometry errors)
        self._rng = np.random.default_rng(seed)
        loaded = world_load.load(path, self._rng)
        self.resolution_m = loaded.resolution_m
        self.ppm = loaded.ppm
        self.interval_us = loaded.interval_us
        self.interval_sim_s = self.interval_us / 1e6
        self.quit_time_s = loaded.quit_time_s
        self.speedup = loaded.speedup
        self.window = loaded.window
        self.threads = loaded.threads
        self.paused = loaded.paused
        self.show_clock = loaded.show_clock
        self.show_clock_interval = loaded.show_clock_interval
        self.models = loaded.models
        self.robots = loaded.robots
        self.space = loaded.space
        self.warnings = loaded.warnings
        self.stageros_warnings = loaded.stageros_warnings
        self._ray_zs = loaded.ray_zs
        self._statics = loaded.statics
        self._static_cells = loaded.static_cells
        self._occupancy = None
        self.sim_time_us = 0
        self.updates = 0
        self.seed = seed
        self.random = Random(1 if seed is None else seed)
        self.rand48 = Rand48(seed)
        self.noise = RangerNoise(self.random)
        self.scheduler = Scheduler(self.threads, self.random)
        self.ctrlargs = ctrlargs
        self.log = controllers.default_log     # run-time errors of controllers; a node's own
        self._robot_of = {r.model: r for r in self.robots}
        self._rank = _ranks(self.models, model_order)
        self.stage_order = sorted(self.models, key=self._rank.__getitem__)
        self._movers = sorted(self.robots, key=lambda r: self._rank[r.model])
        self.energy = Energy(self, self._rank.__getitem__)   # energy.py: packs, charging
        self.scheduler.lifecycle = self.energy
        self._prepare_rays()
        # the fiducial finders' and blobfinders' world: the fiducial-bearing models, the rays
        self.fiducial_index = FiducialIndex(self.models, rank=self._rank.__getitem__)
        self.sight = Sight(self.models, self.robots, self.space)
        # the cameras stageros publishes (camera.py); they draw before the step's moves
        self.cameras = CameraRig(self.models, self.robots, self._statics, self.ppm,
                                 self.window, self.warnings)
        for m in self.models:           # Model::Load's Subscribe of an `alwayson` model
            if m.alwayson:
                self.subscribe(m)
        controllers.start(self)
        if stageros:
            self.subscribe_stageros()

    def subscribe_stageros(self):
        """stageros's SubscribeModels: each robot in order, then the rangers it carries."""
        for r in self.robots:
            self.subscribe(r.model)
            for v in r.rangers:
                self.subscribe(v.model)

    def subscribe(self, model):
        """Model::Subscribe (a controller's, or stageros's)."""
        self.scheduler.subscribe(model, self.sim_time_us)

    def unsubscribe(self, model):
        """Model::Unsubscribe; a position model's last one stops it (goal and velocity 0)."""
        if self.scheduler.unsubscribe(model) and model in self._robot_of:
            r = self._robot_of[model]
            r.goal = (0.0, 0.0, 0.0, 0.0)
            r.control_mode = 'velocity'
            r.velocity = (0.0, 0.0, 0.0, 0.0)

    def robot_of(self, model):
        """The Robot of a position model (None for other models)."""
        return self._robot_of.get(model)

    def handle(self, model):
        """The model as a controller sees it (stage_api)."""
        return api_of(self, model)

    # ---- the interface -------------------------------------------------------------------
    def set_command(self, i, vx, vy, wz):
        """stageros's cmdvelReceived: SetSpeed(x, y, a), applied at the robot's next update.
        Raises ValueError on NaN or infinity (the node refuses those with a WARN)."""
        vx, vy, wz = (finite_float(name, v)
                      for name, v in (('linear.x', vx), ('linear.y', vy), ('angular.z', wz)))
        self.robots[i].goal = (vx, vy, 0.0, wz)
        self.robots[i].control_mode = 'velocity'

    def stop_all(self):
        """stageros's watchdog: SetSpeed(0, 0, 0) on every robot."""
        for r in self.robots:
            r.goal = (0.0, 0.0, 0.0, 0.0)
            r.control_mode = 'velocity'

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
        scheduler = self.scheduler
        self.fiducial_index.begin_step()
        updated = [scheduler.due(0, now)]
        for m in updated[0]:
            r = self._robot_of.get(m)
            if r is not None:
                self._update_position(r, dt, scheduler.subscribed(m))
            elif isinstance(m, Blobfinder):
                m.update(self.sight, (self.updates + 1) % 2)
        self.cameras.update(now)
        layer = self.updates % 2
        for r in self._movers:                    # Stage's active_velocity, in its order
            old = r.pose
            if scheduler.subscribed(r.model):
                self._move(r, dt, layer)
            new = r.pose
            r.truth_twist = ((new[0] - old[0]) / dt, (new[1] - old[1]) / dt,
                             stage_normalize(new[2] - old[2]) / dt)
        for queue in range(1, self.threads + 1):
            updated.append(scheduler.due(queue, now))
        rangers = [m for models in updated for m in models if m in self._sensor_ids]
        if rangers:
            self.cast_rays([k for g in rangers for k in self._sensor_ids[g]],
                           (self.updates + 1) % 2)
        for models in updated[1:]:
            for m in models:
                if isinstance(m, Fiducial):
                    m.update(self.fiducial_index, self.sight, (self.updates + 1) % 2)
        for models in updated:
            for m in models:
                if scheduler.has_callbacks(m, CB_UPDATE):
                    scheduler.call(m, CB_UPDATE)
        scheduler.call_world(self)
        self.energy.update()                # Stage's UpdateCharge of active_energy
        if rangers:
            self._refresh_views(rangers)    # what stageros then reads, callbacks' changes in
        self.updates += 1

    # ---- Stage's position model ------------------------------------------------------------
    def _update_position(self, r, dt, subscribed=True):
        """ModelPosition::Update: the goal turned into the velocity (only while subscribed:
        a model nobody subscribes keeps its velocity), then the estimate."""
        m = r.model
        if subscribed:
            vel = r.commanded_velocity(dt)
            self.energy.position_updated(m, vel)
            for k, (lo, hi) in enumerate(m.velocity_bounds):
                vel[k] = lo if vel[k] < lo else (hi if vel[k] > hi else vel[k])
            r.velocity = tuple(vel)
        else:
            vel = [0.0, 0.0, 0.0, 0.0]
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
        """Every sensor of every ranger the robots carry, in order, the tables of a cast of
        them all, and the beam arrays their readings live in (each sensor's `ranges` and
        `intensities` are views into them)."""
        self._sensors = [(g, s) for r in self.robots for g in r.ranger_models
                         for s in g.sensors]
        self._sensor_ids = {}
        for k, (g, _) in enumerate(self._sensors):
            self._sensor_ids.setdefault(g, []).append(k)
        self._all_sensors = list(range(len(self._sensors)))
        self._rays = self._ray_tables(self._all_sensors)
        self._subset_cache = {}
        offsets = self._rays['offsets']
        self._beam_ranges = np.zeros(int(offsets[-1]), np.float64)
        self._beam_intensities = np.zeros(int(offsets[-1]), np.float64)
        for k, (_, s) in enumerate(self._sensors):
            s.ranges = self._beam_ranges[offsets[k]:offsets[k + 1]]
            s.ranges[:] = s.range[1]
            s.intensities = self._beam_intensities[offsets[k]:offsets[k + 1]]
        self._views_of = {v.model: v for r in self.robots for v in r.rangers}
        self._noise = dict(
            rmax=np.array([s.range[1] for _, s in self._sensors], np.float64),
            prop=np.array([s.noise[1] for _, s in self._sensors], np.float64),
            const=np.array([s.noise[0] for _, s in self._sensors], np.float64),
            angular=np.array([s.noise[2] != 0.0 for _, s in self._sensors], np.bool_))

    def _ray_tables(self, due):
        """The per-sensor tables of the sensors `due` (indices into _sensors) for
        Space.cast."""
        sensors = [self._sensors[k] for k in due]
        counts = np.array([s.samples for _, s in sensors], np.int64)
        return dict(
            offsets=np.concatenate(([0], np.cumsum(counts))).astype(np.int64),
            sensor=np.repeat(np.arange(len(sensors), dtype=np.int64), counts),
            incr=np.array([Ranger.sample_increment(s) for _, s in sensors], np.float64),
            rmax=np.array([s.range[1] for _, s in sensors], np.float64),
            ray_class=np.array([self._ray_zs.index(g.ray_origin(s)[2]) for g, s in sensors],
                               np.int64),
            root=np.array([g.root.index for g, _ in sensors], np.int64),
            origins=np.empty((len(sensors), 4), np.float64))

    def _subset_tables(self, positions):
        """_ray_tables of some sensors, kept for the next step that casts the same ones (in
        Stage's own program only the controllers' rangers update, the same every step)."""
        key = tuple(positions)
        cached = self._subset_cache.get(key)
        if cached is None:
            if len(self._subset_cache) > 64:
                self._subset_cache.clear()
            cached = self._subset_cache[key] = self._ray_tables(positions)
        return cached

    def _refresh_views(self, rangers):
        """stageros's views of the rangers that updated: their first sensor's readings."""
        views = self._views_of
        for g in rangers:
            v = views.get(g)
            if v is not None:
                s = v.sensor
                v.ranges[:] = s.ranges
                v.intensities[:] = s.intensities
                v.has_data = True

    def cast_rays(self, due=None, layer=None):
        """Casts the rays of the sensors `due` (indices into the world's sensors, in the
        order their noise is drawn; default all) from the robots' poses now, through `layer`
        (default: the one the next step's rays read), and stores each sensor's readings."""
        if layer is None:
            layer = (self.updates + 1) % 2
        due = self._all_sensors if due is None else due
        every = len(due) == len(self._sensors)
        positions = self._all_sensors if every else sorted(due)
        tables = self._rays if every else self._subset_tables(positions)
        origins = tables['origins']
        for i, k in enumerate(positions):
            g, s = self._sensors[k]
            origins[i] = g.ray_origin(s)
        rng, hit = self.space.cast(origins, tables['incr'], tables['offsets'], tables['sensor'],
                                   tables['rmax'], tables['ray_class'], tables['root'], layer)
        rr = self.space.model_rr
        intensities = np.where(hit >= 0, rr[np.maximum(hit, 0)], 0.0)
        offsets = tables['offsets']
        row = {k: i for i, k in enumerate(positions)}
        self._draw_noise(rng, offsets, [row[k] for k in due], positions, layer)
        if every:
            self._beam_ranges[:] = rng
            self._beam_intensities[:] = intensities
        else:
            for i, k in enumerate(positions):
                _, s = self._sensors[k]
                s.ranges[:] = rng[offsets[i]:offsets[i + 1]]
                s.intensities[:] = intensities[offsets[i]:offsets[i + 1]]

    def _draw_noise(self, rng, offsets, rows, positions, layer):
        """Stage's draws of each sensor (rows of the cast, in Stage's order), noise added to
        rng in place; a sensor with angular noise casts its beams again, one at a time, at
        the angles its draws turn them to."""
        sensor_of = np.asarray(positions, np.int64)
        angular = self._noise['angular'][sensor_of]
        if not angular.any():
            self.noise.apply_rows(rng, offsets, np.asarray(rows, np.int64),
                                  self._noise['rmax'][sensor_of],
                                  self._noise['prop'][sensor_of],
                                  self._noise['const'][sensor_of])
            return
        for i in rows:
            g, s = self._sensors[positions[i]]
            beams = slice(offsets[i], offsets[i + 1])
            if not angular[i]:
                self.noise.apply_rows(rng, offsets, np.array([i], np.int64),
                                      self._noise['rmax'][sensor_of],
                                      self._noise['prop'][sensor_of],
                                      self._noise['const'][sensor_of])
                continue
            rng[beams] = self._angular_scan(g, s, layer)

    def _angular_scan(self, g, s, layer):
        """A sensor with angular noise, beam by beam as Sensor::Update casts it: each beam's
        angle (kept as a float, as Stage's is) turned by its draw, cast, then its range
        noise drawn."""
        x, y, z, a = g.ray_origin(s)
        incr = Ranger.sample_increment(s)
        tables = self._ray_tables([self._sensors.index((g, s))])
        tables['sensor'] = np.zeros(1, np.int64)
        tables['offsets'] = np.array([0, 1], np.int64)
        out = np.empty(s.samples, np.float64)
        for t in range(s.samples):
            saved = float(np.float32(a))
            turned = float(np.float32(a + incr * s.noise[2] * self.noise.angle_noise() * 0.5))
            tables['origins'][0] = (x, y, z, turned)
            rng, _ = self.space.cast(tables['origins'], tables['incr'], tables['offsets'],
                                     tables['sensor'], tables['rmax'], tables['ray_class'],
                                     tables['root'], layer)
            out[t] = self.noise.range_noise(float(rng[0]), s.range[1], s.noise)
            a = saved + incr
        return out

    def scan_from(self, view, pose):
        """The ranges (float32) `view` reads with its robot at `pose` (x, y, z, a), through
        the layer the last step's rays read. In Stage the rangers run in a worker thread
        beside the moves: now and then one starts before its robot has moved, and its scan
        is this one with the robot's pose before the step."""
        robot = view.model.parent
        keep = robot.pose
        robot.pose = pose
        try:
            tables = self._ray_tables([self._sensors.index((view.model, view.sensor))])
            tables['origins'][0] = view.model.ray_origin(view.sensor)
        finally:
            robot.pose = keep
        rng, _ = self.space.cast(tables['origins'], tables['incr'], tables['offsets'],
                                 tables['sensor'], tables['rmax'], tables['ray_class'],
                                 tables['root'], self.updates % 2)
        return rng.astype(np.float32)

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


def load_world(path, seed=None, stageros=True, ctrlargs='', model_order=None):
    """Parses the world file (includes, bitmaps) into a World and starts its controllers
    (see World); raises WorldError."""
    if not os.path.isfile(path):
        raise WorldError(path, None, 'the world file does not exist')
    return World(path, seed, stageros, ctrlargs, model_order)


def _ranks(models, model_order):
    """Each model's place in Stage's World::models: by model_order's tokens where it names
    them, the others after, in file order."""
    if not model_order:
        return {m: m.index for m in models}
    named = {token: k for k, token in enumerate(model_order)}
    return {m: (named.get(m.token, len(named) + m.index)) for m in models}
