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
   robot's pose after the move (with several worker threads, those that race.py's model
   of Stage's race starts before their robot's move: from the pose before it), through
   layer ((updates + 1) % 2): the bodies as drawn in the previous step
   (STAGE_RAYS_READ_LAST_LAYER; in Stage the rangers run in worker threads beside the
   moves), then draws its noise from random() beam by beam (noise.py); each fiducial
   finder looks for the fiducial-bearing models around it;
4. the update callbacks of every model that updated (the controllers), queue by queue, then
   the world's callbacks, then the energy model's charge update (energy.py);
5. stageros publishes: odom = the estimate and the velocity, ground truth = the world pose.
"""
import bisect
import gc
import math
import os

import numpy as np

from . import controllers, floor, world_load
from .blobfinder import Blobfinder
from .camera import CameraRig
from .casts import RangerCasts
from .energy import Energy
from .fiducial import Fiducial, FiducialIndex
from .finders import prepare_ids as prepare_finders
from .glibc_random import Rand48, Random
from .motion import Chains, Motion, elements
from .noise import RangerNoise
from .robot_state import MODE_CODE, RobotArrays
from .runtime_models import redraw_if_changed
from .scheduler import CB_UPDATE, Scheduler
from .sensing import sense
from .sight import Sight
from .stage_api import api_of
from .step_each import RobotByRobot
from .worldfile import WorldError

__all__ = ['World', 'WorldError', 'load_world']

VELOCITY = MODE_CODE['velocity']    # Stage's CONTROL_VELOCITY: what cmd_vel sets


class World(RangerCasts, RobotByRobot):
    """A loaded world. Use load_world()."""

    def __init__(self, path, seed=None, stageros=True, ctrlargs='', model_order=None,
                 race=True, run=None):
        """seed: random()'s srandom and drand48's srand48 (default: an unseeded process's,
        srandom(1) and glibc's zero drand48 state; loading draws from drand48 too) and the
        worker-thread race's generator (race.py; seed None draws as seed 1);
        run: one of the runs the real Stage makes of the world: what Stage draws from the
        clock (its srand48(time) at start, so drand48, loading's draws included; fasr2's
        srandom(time)) and its worker threads' race, from the number `run`; random()
        stays seed's (an unseeded Stage's srandom(1) without it), as in every Stage run;
        stageros: subscribe every robot and its rangers as stageros does (else only what
        the controllers subscribe, as Stage's `stage`); ctrlargs: `stage -a`'s argument
        string, World::ctrlargs, given to every controller; model_order: the models'
        tokens in the order of Stage's World::models, a set of pointers ordered by the
        models' addresses in memory (STAGE_MODEL_POINTER_ORDER): the order Stage starts the
        controllers, moves the robots and lists a finder's readings in. It follows nothing
        in the world (the same at every run of one program); without it, file order.
        race: with several worker threads, model Stage's race (race.py; False: every ranger
        casts after the moves)."""
        self.path = path
        # what Stage seeds from the clock: the run's number, else the world's seed
        self.clock_seed = seed if run is None else int(run)
        # drand48(), drawn from while loading too (odometry errors, random colours)
        self.rand48 = Rand48(self.clock_seed)
        loaded = world_load.load(path, self.rand48)
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
        # every robot's state, and its position model's pose, as rows of one set of arrays
        self.state = RobotArrays(len(self.robots))
        for r in self.robots:
            r.bind(self.state)
        # robots carried by another model: their rows are poses in the carrier's frame
        self._carried_robots = [r.index for r in self.robots if r.model.parent is not None]
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
        # the robots' updates and moves in kernels, when every robot is a top-level model
        # (its pose its world pose) moved in file order (no other model order given); else
        # robot by robot (_step_each)
        fast = (all(r.model.parent is None for r in self.robots)
                and self._movers == self.robots)
        self._packs = self.energy.has_packs()
        self.motion = Motion(self.robots, self.space) if fast else None
        self._robot_slot = np.full(len(self.models), -1, np.int64)
        for r in self.robots:
            self._robot_slot[r.model.index] = r.index
        self._kind = {k: np.array([isinstance(m, k) for m in self.models], np.bool_)
                      for k in (Blobfinder, Fiducial)}
        self._any_finder = bool(self._kind[Fiducial].any())
        self._any_blobfinder = bool(self._kind[Blobfinder].any())
        self._masks_version = None
        self._model_chains = None        # every model's chain, made when first needed
        # (model index, body) -> a static model's global pose, and (the indices' bytes,
        # body) -> global_poses's plan for those models, forgotten whenever a static model
        # is moved or resized or a model is made (runtime_models)
        self._static_poses = {}
        # what models made, moved or recoloured at run time leave for the next step
        # (runtime_models): a static model's drawing, a robot's tree
        self._statics_changed = False
        self._trees_changed = False
        self._models_by_token = None     # Stage's models_by_name, made when first asked
        self._top_counts = None          # Stage's child_type_counts, made when first needed
        self._world_api = None           # what controllers see (stage_api): the world
        self._handles = {}               # and each model, one handle each
        self._root_of = np.array([m.root.index for m in self.models], np.int64)
        # controllers' callbacks of one batch run together (scheduler.py); False: each on
        # its own (the same run: the tests compare the two)
        self.batches = True
        self._prepare_rays()
        self.race = self._worker_race(self.clock_seed) if race else None  # who casts first
        # the fiducial finders' and blobfinders' world: the fiducial-bearing models, the rays
        self.fiducial_index = FiducialIndex(self.models, rank=self._rank.__getitem__)
        if self.motion is not None:
            self.fiducial_index.poses = self.global_poses
        self.sight = Sight(self.models, self.robots, self.space)
        # the cameras stageros publishes (camera.py); they draw before the step's moves
        self.cameras = CameraRig(self.models, self.robots, self._statics, self.ppm,
                                 self.window, self.warnings)
        for m in self.models:           # Model::Load's Subscribe of an `alwayson` model
            if m.alwayson:
                self.subscribe(m)
        # your own controllers may read any finder's readings at any time: then every
        # finder makes them all (Stage's own read what they say: FiducialApi.read_nearest_only)
        self.fiducial_index.nearest_only_allowed = not controllers.start(self)
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

    def robot_poses(self):
        """Every robot's world pose (x, y, yaw), as Robot.pose gives it: an (n, 3) array."""
        poses = self.state.pose[:, [0, 1, 3]]
        for i in self._carried_robots:
            poses[i] = self.robots[i].pose
        return poses

    def global_poses(self, models, body=False, at=None):
        """Model.global_pose (body_pose with body: one bool for all, or one per model) of
        each model, an (n, 4) array: carried from the robots' poses by motion.Chains' kernel
        for the models of robot trees (at: their indices, if the caller has them), by
        Model.global_pose for static ones."""
        if at is None:
            at = np.fromiter((m.index for m in models), np.int64, len(models))
        key = (at.tobytes(), body if isinstance(body, bool) else np.asarray(body).tobytes())
        plan = self._static_poses.get(key)
        if plan is None:
            plan = self._static_poses[key] = self._pose_plan(models, body, at)
        rows, static, static_rows = plan
        if rows is None:                    # static models only (the finders' sets)
            return static_rows.copy()
        out = np.empty((len(models), 4), np.float64)
        self._model_chains.poses(rows, self.state.pose, out)
        if static_rows is not None:         # their chains start at robot 0: rows replaced
            out[static] = static_rows
        return out

    def _pose_plan(self, models, body, at):
        """global_poses's (chain rows or None, the static models' places, their rows) of
        these models, kept until a model is made, moved or resized (runtime_models)."""
        static = np.flatnonzero(self._robot_slot[self._root_of[at]] < 0)
        if len(static) == len(models):
            return None, static, self._static_pose_rows(models, range(len(models)), body)
        if self._model_chains is None:
            n = len(self.models)
            slots = [max(0, self._robot_slot[m.root.index]) for m in self.models]
            self._model_chains = Chains(
                [(r, elements(m)) for r, m in zip(slots, self.models, strict=True)]
                + [(r, elements(m, [m.geom_pose])) for r, m in zip(slots, self.models,
                                                                  strict=True)])
            self._model_chains.count = n
        rows = at + self._model_chains.count * np.asarray(body, np.int64)
        return (rows, static,
                self._static_pose_rows(models, static.tolist(), body) if len(static) else None)

    def _static_pose_rows(self, models, which, body):
        """python_poses of models[k] for k in which, static models: from the cache."""
        cache = self._static_poses
        rows = []
        for k in which:
            m = models[k]
            b = bool(body if isinstance(body, (bool, np.bool_)) else body[k])
            pose = cache.get((m.index, b))
            if pose is None:
                pose = cache[m.index, b] = m.body_pose() if b else m.global_pose()
            rows.append(pose)
        return np.array(rows, np.float64).reshape(-1, 4)

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
        goal = (finite_float('linear.x', vx), finite_float('linear.y', vy), 0.0,
                finite_float('angular.z', wz))
        goals, modes, row = self.robots[i].command_rows()    # a swarm's cmd_vels: no properties
        goals[row] = goal
        modes[row] = VELOCITY

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
        """One World::Update (see the module docstring): every robot's update and move in
        motion.py's kernels (or robot by robot, _step_each, when a robot stands on another
        model), the updates of a queue taken as the models' indices."""
        redraw_if_changed(self)     # models made, moved or resized since (runtime_models)
        if self.motion is None:
            self._step_each()
            return
        self.sim_time_us += self.interval_us
        now = self.sim_time_us
        dt = self.interval_us / 1e6
        scheduler = self.scheduler
        models = self.models
        sensing = (self.updates + 1) % 2
        subscribed, with_callbacks = self._masks()
        if self._any_finder:     # the finders' sets (with no finder, nobody reads them)
            self.fiducial_index.begin_step()
        updated = [scheduler.due_indices(0, now)]
        slots = self._robot_slot[updated[0]]
        slots = slots[slots >= 0]
        if self._packs:      # the power each update draws, from the velocity it is commanded
            for s in slots[subscribed[slots]].tolist():
                r = self.robots[s]
                self.energy.position_updated(r.model, r.commanded_velocity(dt))
        self.motion.update(self.robots, self.state, slots, subscribed, dt)
        if self._any_blobfinder:
            for i in updated[0][self._kind[Blobfinder][updated[0]]].tolist():
                models[i].update(self.sight, sensing)     # beside the position updates
        self.cameras.update(now)
        before = self.state.pose.copy() if self.race is not None else None
        self.motion.move(self.state, subscribed, dt, self.updates % 2)
        for queue in range(1, self.threads + 1):
            updated.append(scheduler.due_indices(queue, now))
        every = np.concatenate(updated)
        rangers = self._ranger_slot[every]
        is_ranger = rangers >= 0
        rangers = rangers[is_ranger]
        casting = finding = None
        if rangers.size:
            casting = self.ranger_slots_casting(rangers, sensing,
                                                self._stale(updated, is_ranger), before)
        if self._any_finder:
            is_finder = self._kind[Fiducial]
            finders = [ids[is_finder[ids]] for ids in updated[1:]]
            finders = np.concatenate(finders) if finders else None
            if finders is not None and finders.size:
                finding = prepare_finders(finders, models.__getitem__, self.fiducial_index,
                                          self.sight, sensing)
        sense(casting, finding)     # the rays and the finders, in one region when worth it
        if casting is not None:
            self.end_casts(casting)
        if finding is not None:
            finding.publish()
        self._call_updates(every, with_callbacks)
        scheduler.call_world(self)
        if self._packs:
            self.energy.update()            # Stage's UpdateCharge of active_energy
        if rangers.size:
            self._refresh_view_slots(rangers)   # what stageros then reads, callbacks' changes in
        self.updates += 1

    def _masks(self):
        """(per robot: subscribed; per model: has update callbacks), remade when the
        scheduler's subscriptions or callbacks have changed, and with them the batches
        (scheduler.py): per model, its only update callback's batch (its number, 0 for
        none) and its row in that batch's plan."""
        scheduler = self.scheduler
        if self._masks_version != scheduler.version:
            self._subscribed = np.array([scheduler.subscribed(r.model) for r in self.robots],
                                        np.bool_)
            entries = [scheduler.callbacks.get((m, CB_UPDATE)) for m in self.models]
            self._with_callbacks = np.array([bool(e) for e in entries], np.bool_)
            self._batches = [None]
            self._batch_entries = [None]
            self._batch_id = np.zeros(len(self.models), np.int64)
            self._batch_row = np.zeros(len(self.models), np.int64)
            for i, e in enumerate(entries):
                batch = getattr(e[0][0], 'batch', None) if e and len(e) == 1 else None
                if batch is None or not self.batches:
                    continue
                if batch not in self._batches:
                    self._batches.append(batch)
                    self._batch_entries.append([])
                b = self._batches.index(batch)
                self._batch_id[i] = b
                self._batch_row[i] = len(self._batch_entries[b])
                self._batch_entries[b].append(e[0])
            self._plans = {}
            self._masks_version = scheduler.version
        return self._subscribed, self._with_callbacks

    def _call_updates(self, every, with_callbacks):
        """The update callbacks of the models `every` (indices, in update order) that have
        some, each model's when its turn comes (a callback may add or remove others); runs
        of models of one batch together."""
        scheduler = self.scheduler
        models = self.models
        # Python lists for the loop (a step calls a few callbacks, and numpy's calls on a few
        # numbers cost more than the loop); arrays for a batch's rows
        order = every.tolist()
        at, bids, ends = self._callback_runs(every, with_callbacks, 0)
        j = 0
        while j < len(at):
            p = int(at[j])
            b = bids[j]
            if b:
                k = ends[bisect.bisect_right(ends, j)]      # the end of its batch's run
                done = self._run_batch(b, self._batch_row[every[at[j:k]]])
                j += done
                if done:
                    continue
            version = scheduler.version
            scheduler.call(models[order[p]], CB_UPDATE)
            j += 1
            if scheduler.version != version:      # callbacks changed: look again
                _, with_callbacks = self._masks()
                rest, bids_rest, _ = self._callback_runs(every, with_callbacks, p + 1)
                at = np.concatenate((at[:j], rest))
                bids = bids[:j] + bids_rest
                ends = self._run_ends(np.array(bids, np.int64))

    def _callback_runs(self, every, with_callbacks, start):
        """(the places in `every` from `start` on of the models with update callbacks, an
        array; their batches, a list; the ends of the runs of one batch, a list)."""
        at = start + np.flatnonzero(with_callbacks[every[start:]])
        bids = self._batch_id[every[at]]
        return at, bids.tolist(), self._run_ends(bids)

    @staticmethod
    def _run_ends(bids):
        """Where each run of equal batch numbers (an array) ends (exclusive), in order."""
        return (np.flatnonzero(bids[1:] != bids[:-1]) + 1).tolist() + [len(bids)]

    def _run_batch(self, b, rows):
        """Batch b's callbacks of the rows `rows` (its plan's), in turn: how many were
        done (0: call the first on its own)."""
        plan = self._plans.get(b, False)
        if plan is False:
            plan = self._plans[b] = self._batches[b].prepare(self._batch_entries[b])
        return 0 if plan is None else self._batches[b].run(plan, rows)

    # ---- pictures and maps ---------------------------------------------------------------
    def occupancy(self):
        """(grid bool [rows, cols] of the static bodies, filled, origin_x, origin_y,
        resolution_m); row 0 is the lowest y. Computed once."""
        redraw_if_changed(self)
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


def load_world(path, seed=None, stageros=True, ctrlargs='', model_order=None, race=True,
               run=None):
    """Parses the world file (includes, bitmaps) into a World and starts its controllers
    (see World); raises WorldError."""
    if not os.path.isfile(path):
        raise WorldError(path, None, 'the world file does not exist')
    # loading makes objects by the million in a swarm and frees few: the cyclic collector's
    # passes over them would cost a third of the time (10,000 swarmbots: 12 s of CPU to 8)
    collecting = gc.isenabled()
    gc.disable()
    try:
        return World(path, seed, stageros, ctrlargs, model_order, race, run)
    finally:
        if collecting:
            gc.enable()


def _ranks(models, model_order):
    """Each model's place in Stage's World::models: by model_order's tokens where it names
    them, the others after, in file order."""
    if not model_order:
        return {m: m.index for m in models}
    named = {token: k for k, token in enumerate(model_order)}
    return {m: (named.get(m.token, len(named) + m.index)) for m in models}
