"""The rangers' rays of a World (no rospy): every sensor's tables, the casts of a step's due
sensors (raytrace.py's kernels through Space.cast), their noise in Stage's order (noise.py),
and stageros's views of them.

Every sensor's readings live in two beam arrays (each sensor's `ranges` and `intensities`
are views into them), and so do the views stageros publishes (each ranger's first sensor as
a float32 scan), so that a step stores and refreshes them with a few array operations. The
rays leave from each sensor's pose on its robot, carried from the robot's pose by
motion.Chains (Ranger.ray_origin's sums, in a kernel) when the World moves its robots by
motion.py, else by Ranger.ray_origin itself.
"""
import numpy as np

from .jit import kernel, njit
from .motion import Chains, elements
from .race import WorkerRace
from .ranger import Ranger
from .space import run_cast


@njit(cache=True)
def _sorted_due(due, n):
    """np.sort(due) of sensor indices below n (a counting sort), and per due sensor the
    place of its last and of its first copy there (searchsorted right - 1, and left)."""
    count = np.zeros(n, np.int64)
    for i in range(due.shape[0]):
        count[due[i]] += 1
    start = np.empty(n, np.int64)
    k = 0
    for v in range(n):
        start[v] = k
        k += count[v]
    positions = np.empty(due.shape[0], np.int64)
    for v in range(n):
        for j in range(count[v]):
            positions[start[v] + j] = v
    last = np.empty(due.shape[0], np.int64)
    first = np.empty(due.shape[0], np.int64)
    for i in range(due.shape[0]):
        first[i] = start[due[i]]
        last[i] = start[due[i]] + count[due[i]] - 1
    return positions, last, first


@kernel
def _store_beams(rng, hit, rr, beams, ranges, intensities):
    """A cast's beams into the world's beam arrays at `beams`: each range, and the
    ranger_return (rr) of the model it hit as its intensity (0 for none)."""
    for k in range(rng.shape[0]):
        ranges[beams[k]] = rng[k]
        intensities[beams[k]] = rr[hit[k]] if hit[k] >= 0 else 0.0


@njit(cache=True)
def _slot_rows(slots, off, n, stale):
    """_sorted_due of the sensors of the ranger slots `slots` (ranger k's sensors
    off[k]..off[k + 1] - 1, in the slots' order): (the positions, each due sensor's row (its
    last copy's)), and per position whether it casts from before the move: the first copy
    of a sensor of a slot whose `stale` is true (stale empty: none)."""
    due = _ranges_of(off[slots], off[slots + 1])
    positions, last, first = _sorted_due(due, n)
    stale_rows = np.zeros(due.shape[0], np.bool_)
    if stale.shape[0]:
        k = 0
        for j in range(slots.shape[0]):
            for _ in range(off[slots[j]], off[slots[j] + 1]):
                if stale[j]:
                    stale_rows[first[k]] = True
                k += 1
    return positions, last, stale_rows


@kernel
def _copy_views(slots, src_off, dst_off, count, beam_ranges, beam_intensities, view_ranges,
                view_intensities):
    """The views of the rangers `slots`: each view's count[k] beams from src_off[k] in the
    beam arrays to dst_off[k] in the views' float32 arrays."""
    for k in slots:
        for t in range(count[k]):
            view_ranges[dst_off[k] + t] = beam_ranges[src_off[k] + t]
            view_intensities[dst_off[k] + t] = beam_intensities[src_off[k] + t]


@njit(cache=True)
def _ranges_of(starts, ends):
    """The integers starts[0]..ends[0]-1, starts[1]..ends[1]-1, ... in one int64 array."""
    total = 0
    for i in range(starts.shape[0]):
        total += ends[i] - starts[i]
    out = np.empty(total, np.int64)
    k = 0
    for i in range(starts.shape[0]):
        for v in range(starts[i], ends[i]):
            out[k] = v
            k += 1
    return out


class Casting:
    """A step's rays made ready (RangerCasts.begin_casts): args, raytrace.cast_scans's
    (ranges and models hit into its last two arrays), and what end_casts reads."""

    __slots__ = ('args', 'tables', 'positions', 'rows', 'stale_rows', 'layer')

    def __init__(self, args, tables, positions, rows, stale_rows, layer):
        self.args = args
        self.tables = tables
        self.positions = positions
        self.rows = rows
        self.stale_rows = stale_rows
        self.layer = layer

    def rays(self):
        return self.args[3].shape[0]


class RangerCasts:
    """The World's rays (a part of World: it uses the world's robots, space, state, noise,
    motion and updates)."""

    def _prepare_rays(self):
        """Every sensor of every ranger the robots carry, in order, the tables of a cast of
        them all, and the beam arrays their readings live in (each sensor's `ranges` and
        `intensities` are views into them)."""
        self._sensors = [(g, s) for r in self.robots for g in r.ranger_models
                         for s in g.sensors]
        self._sensor_ids = {}
        for k, (g, _) in enumerate(self._sensors):
            self._sensor_ids.setdefault(g, []).append(k)
        self._rays = self._ray_tables(range(len(self._sensors)))
        self._rays['beams'] = np.arange(self._rays['offsets'][-1], dtype=np.int64)
        self._subset_cache = {}
        offsets = self._rays['offsets']
        self._beam_ranges = np.zeros(int(offsets[-1]), np.float64)
        self._beam_intensities = np.zeros(int(offsets[-1]), np.float64)
        for k, (_, s) in enumerate(self._sensors):
            s.ranges = self._beam_ranges[offsets[k]:offsets[k + 1]]
            s.beams = self._beam_ranges
            s.beam_at = int(offsets[k])
            s.ranges[:] = s.range[1]
            s.intensities = self._beam_intensities[offsets[k]:offsets[k + 1]]
        self._views_of = {v.model: v for r in self.robots for v in r.rangers}
        self._prepare_slots(offsets)

    def _prepare_slots(self, offsets):
        """The rangers by slot (their order in the sensors), the models' ranger slots, the
        robots' sensors' chains, and the views' float32 arrays."""
        rangers = list(self._sensor_ids)
        self._ranger_slot = np.full(len(self.models), -1, np.int64)
        for k, g in enumerate(rangers):
            self._ranger_slot[g.index] = k
        self._ranger_models = rangers
        self._ranger_sensor_off = np.array(
            [self._sensor_ids[g][0] for g in rangers] + [len(self._sensors)], np.int64)
        self._all_sensors = np.arange(len(self._sensors), dtype=np.int64)
        carried = [(r.index, g, s) for r in self.robots for g in r.ranger_models
                   for s in g.sensors]
        # a ranger's sensors share its body's frame (computed once per ranger and cast)
        chain = {}
        for _, g, _ in carried:
            if g not in chain:
                chain[g] = elements(g, [g.geom_pose])
        # elements(g, [g.geom_pose, g.ray_local(s)]): the ranger's chain then a plain tail
        self._sensor_robot = np.array([r for r, _, _ in carried], np.int64)
        self._top_level_robots = all(r.model.parent is None for r in self.robots)
        self._origin_chains = Chains(
            [(r, chain[g] + [(tuple(g.ray_local(s)), False, 0.0)]) for r, g, s in carried],
            [(g.index, len(chain[g])) for _, g, _ in carried])
        views = [self._views_of.get(g) for g in rangers]
        self._view_of_slot = views
        count = [v.samples if v is not None else 0 for v in views]
        self._view_count = np.array(count, np.int64)
        self._view_dst_off = np.concatenate(([0], np.cumsum(count)[:-1])).astype(np.int64) \
            if count else np.zeros(0, np.int64)
        self._view_src_off = np.array([offsets[self._sensor_ids[g][0]] for g in rangers],
                                      np.int64)
        self._view_ranges = np.zeros(sum(count), np.float32)
        self._view_intensities = np.zeros(sum(count), np.float32)
        for k, v in enumerate(views):
            if v is not None:
                at = slice(self._view_dst_off[k], self._view_dst_off[k] + count[k])
                self._view_ranges[at] = v.ranges
                self._view_intensities[at] = v.intensities
                v.ranges = self._view_ranges[at]
                v.intensities = self._view_intensities[at]
        self._views_without_data = sum(1 for v in views if v is not None and not v.has_data)

    def _worker_race(self, seed):
        """The world's WorkerRace (race.py), None with one worker thread."""
        if not WorkerRace.applies(self.threads):
            return None
        off = self._ranger_sensor_off
        offsets = self._rays['offsets']
        return WorkerRace(self.threads, seed, offsets[off[1:]] - offsets[off[:-1]],
                          self._sensor_robot[off[:-1]], [len(r.block_ids) for r in self.robots],
                          [r.index for r in self._movers])

    def _stale(self, updated, chosen):
        """This step's race: per updated model (`updated`: each queue's, model indices or
        models, in update order) where `chosen` (the rangers), whether it casts from its
        robot's pose before the move; None without a race."""
        if self.race is None:
            return None
        queue = np.repeat(np.arange(len(updated)), [len(u) for u in updated])[chosen]
        if all(isinstance(u, np.ndarray) for u in updated):
            every = np.concatenate(updated)
        else:
            every = np.array([m.index for u in updated for m in u], np.int64)
        moving = (self.state.velocity != 0.0).any(axis=1)
        return self.race.stale(queue, self._ranger_slot[every[chosen]], moving)

    def _ray_tables(self, due):
        """The per-sensor tables of the sensors `due` (indices into _sensors) for
        Space.cast."""
        sensors = [self._sensors[k] for k in due]
        counts = np.array([s.samples for _, s in sensors], np.int64)
        beam_z = {}
        for g in {g for g, _ in sensors}:
            beam_z.update((id(s), o[2]) for s, o in zip(g.sensors, g.ray_origins(), strict=True))
        prop = np.array([s.noise[1] for _, s in sensors], np.float64)
        const = np.array([s.noise[0] for _, s in sensors], np.float64)
        return dict(
            offsets=np.concatenate(([0], np.cumsum(counts))).astype(np.int64),
            sensor=np.repeat(np.arange(len(sensors), dtype=np.int64), counts),
            incr=np.array([Ranger.sample_increment(s) for _, s in sensors], np.float64),
            rmax=np.array([s.range[1] for _, s in sensors], np.float64),
            # their noise (noise.py): const, prop, and whether any has angular noise
            prop=prop, const=const,
            angular=any(s.noise[2] != 0.0 for _, s in sensors),
            ray_class=np.array([self._ray_zs.index(beam_z[id(s)]) for _, s in sensors],
                               np.int64),
            root=np.array([g.root.index for g, _ in sensors], np.int64),
            origins=np.empty((len(sensors), 4), np.float64))

    def _subset_tables(self, positions):
        """_ray_tables of some sensors (an int64 array), with their beams' places in the
        world's beam arrays (`beams`), kept for the next step that casts the same ones (in
        Stage's own program only the controllers' rangers update, the same every step)."""
        key = positions.tobytes()
        cached = self._subset_cache.get(key)
        if cached is None:
            if len(self._subset_cache) > 64:
                self._subset_cache.clear()
            cached = self._subset_cache[key] = self._ray_tables(positions.tolist())
            offsets = self._rays['offsets']
            cached['beams'] = _ranges_of(offsets[positions], offsets[positions + 1])
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

    def _refresh_view_slots(self, slots):
        """_refresh_views of the rangers `slots` (int64 array of ranger slots), at once."""
        _copy_views(slots, self._view_src_off, self._view_dst_off, self._view_count,
                    self._beam_ranges, self._beam_intensities, self._view_ranges,
                    self._view_intensities)
        if self._views_without_data:
            for k in slots.tolist():
                v = self._view_of_slot[k]
                if v is not None and not v.has_data:
                    v.has_data = True
                    self._views_without_data -= 1

    def cast_rays(self, due=None, layer=None, stale=None, before=None):
        """Casts the rays of the sensors `due` (indices into the world's sensors, in the
        order their noise is drawn; default all) from the robots' poses now, through `layer`
        (default: the one the next step's rays read), and stores each sensor's readings.
        stale (bool per due sensor): those cast from their robot's pose `before` this
        step's move instead (race.py; `before`: the robots' poses then, a copy of
        state.pose)."""
        casting = self.begin_casts(due, layer, stale, before)
        run_cast(casting.args)
        self.end_casts(casting)

    def begin_casts(self, due=None, layer=None, stale=None, before=None):
        """cast_rays up to its rays (a Casting: its args for raytrace.cast_scans, in any
        thread); end_casts then stores the readings."""
        due = self._all_sensors if due is None else np.asarray(due, np.int64)
        if len(due) == len(self._sensors):     # each its own row, its only copy
            positions, rows, first = self._all_sensors, due, due
        else:
            positions, rows, first = _sorted_due(due, len(self._sensors))
        stale_rows = None
        if stale is not None and stale.any():
            stale_rows = np.zeros(len(positions), np.bool_)
            stale_rows[first[stale]] = True
        return self._casting(positions, rows, stale_rows, before, layer)

    def _casting(self, positions, rows, stale_rows, before, layer):
        """begin_casts of the sensors `positions` (sorted), rows: each due sensor's row of
        the cast (its last, as a dict of them would say), stale_rows: None or per position
        whether it casts from `before`."""
        if layer is None:
            layer = (self.updates + 1) % 2
        every = len(positions) == len(self._sensors)
        tables = self._rays if every else self._subset_tables(positions)
        origins = tables['origins']
        if self.motion is not None:
            self._origin_chains.poses(positions, self.state.pose, origins)
        else:
            for i, k in enumerate(positions.tolist()):
                g, s = self._sensors[k]
                origins[i] = g.ray_origin(s)
        if stale_rows is not None:
            self._stale_origins(positions, stale_rows, before, origins)
        args = self.space.cast_args(origins, tables['incr'], tables['offsets'],
                                    tables['sensor'], tables['rmax'], tables['ray_class'],
                                    tables['root'], layer)
        return Casting(args, tables, positions, rows, stale_rows, layer)

    def end_casts(self, casting):
        """The readings of a Casting's rays (cast): their intensities, their noise drawn in
        Stage's order, stored in the sensors' beams."""
        rng, hit = casting.args[-2], casting.args[-1]
        tables, positions, stale_rows = casting.tables, casting.positions, casting.stale_rows
        self._draw_noise(rng, tables, casting.rows, positions, casting.layer,
                         None if stale_rows is None
                         else np.where(stale_rows[:, None], tables['origins'], np.nan))
        _store_beams(rng, hit, self.space.model_rr, tables['beams'], self._beam_ranges,
                     self._beam_intensities)

    def ranger_slots_casting(self, slots, layer, stale=None, before=None):
        """begin_casts of every sensor of the rangers `slots` (int64 array of ranger slots,
        in the order they updated); stale: a bool per slot, its sensors cast from
        `before`."""
        positions, rows, stale_rows = _slot_rows(
            slots, self._ranger_sensor_off, len(self._sensors),
            np.zeros(0, np.bool_) if stale is None else stale)
        return self._casting(positions, rows, stale_rows if stale_rows.any() else None,
                             before, layer)

    def _stale_origins(self, positions, stale_rows, before, origins):
        """origins[i] of the sensors positions[i] where stale_rows[i]: from their robots'
        poses `before` the move (rows as state.pose's; see cast_rays)."""
        at = np.flatnonzero(stale_rows)
        if self._top_level_robots:      # the chains carry a robot's pose as ray_origin does
            out = np.empty((at.size, 4), np.float64)
            self._origin_chains.poses(positions[at], before, out)
            origins[at] = out
            return
        for i in at.tolist():
            g, s = self._sensors[positions[i]]
            model = self.robots[self._sensor_robot[positions[i]]].model
            keep = model.pose
            model.pose = tuple(before[self._sensor_robot[positions[i]]])
            try:
                origins[i] = g.ray_origin(s)
            finally:
                model.pose = keep

    def _draw_noise(self, rng, tables, rows, positions, layer, stale_origins=None):
        """Stage's draws of each sensor (rows of the cast of `tables`, _ray_tables's of the
        sensors `positions`, in Stage's order), noise added to rng in place; a sensor with
        angular noise casts its beams again, one at a time, at the angles its draws turn
        them to (from stale_origins' row where it is not NaN)."""
        offsets = tables['offsets']
        rows = np.asarray(rows, np.int64)
        if not tables['angular']:
            self.noise.apply_rows(rng, offsets, rows, tables['rmax'], tables['prop'],
                                  tables['const'])
            return
        for i in rows.tolist():
            g, s = self._sensors[positions[i]]
            if s.noise[2] == 0.0:
                self.noise.apply_rows(rng, offsets, np.array([i], np.int64), tables['rmax'],
                                      tables['prop'], tables['const'])
                continue
            origin = None
            if stale_origins is not None and not np.isnan(stale_origins[i, 0]):
                origin = tuple(stale_origins[i])
            rng[offsets[i]:offsets[i + 1]] = self._angular_scan(g, s, layer, origin)

    def _angular_scan(self, g, s, layer, origin=None):
        """A sensor with angular noise, beam by beam as Sensor::Update casts it: each beam's
        angle (kept as a float, as Stage's is) turned by its draw, cast, then its range
        noise drawn; from `origin` if given, else from the robot's pose now."""
        x, y, z, a = g.ray_origin(s) if origin is None else origin
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

