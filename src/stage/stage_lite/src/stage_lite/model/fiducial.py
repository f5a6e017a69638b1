"""Stage 4.3's fiducial finder (libstage/model_fiducial.cc), rule for rule (no rospy).

Any model may carry a fiducial: `fiducial_return N` (N != 0; negative ids are seen too) and
`fiducial_key K` (default 0), read for every model by models.Model.load. A `fiducial` model
(this module's Fiducial) sees the fiducial-bearing models around it. Its properties, as
ModelFiducial::Load reads them, with Stage's defaults:
- `range_max` (m, 8.0): models at this distance or farther are not seen;
- `range_max_id` (m, 5.0): closer than this a reading carries the model's fiducial_return,
  farther its id is 0;
- `fov` (degrees, 180): the bearing must be within +-fov/2 (ends included);
- `ignore_zloc` (0): 1 sees a model the ray passed over or under (nothing else in the way);
- `range_min` (m, 0.0): read, and used by nothing in Stage 4.3.0 (no clamp).
The finder's own `fiducial_key` (its model property) must equal the target's.

An update (ModelFiducial::Update, then AddModelIfVisible per candidate):
1. the candidates: of the world's fiducial-bearing models (FiducialIndex), those whose
   global x lies in (x - range_max, x + range_max] and y in (y - range_max, y + range_max],
   (x, y) the finder's global position (STAGE_FIDUCIAL_BOX: Stage's sets sorted by x and by
   y, bounded by a stack-allocated dummy model whose address ranks above every model's, so
   a tie at the low edge falls outside and one at the high edge inside);
2. in Stage's ORDER, that of the models' addresses in its heap (the candidates are the
   intersection of two std::sets of pointers: neither x nor y orders them). That order
   follows no rule of the world (STAGE_MODEL_POINTER_ORDER): real Stage 4.3.0 (`stage -g`,
   built on this kind of machine) puts fasr.world's seven charge stations, in file order
   1..7, in the order 1 3 2 6 4 5 7, and pioneer_flocking.world's 100 robots in a shuffle
   starting 0 2 4 14 56 3 12; the same at every run of the same program, but a program that
   allocates otherwise before loading (stageros, the GUI) may differ. Here the order is the
   world file's unless the FiducialIndex is given the real one (`rank`);
3. each candidate is kept if its fiducial_key equals the finder's, range = hypot(dy, dx) <
   range_max, |normalize(atan2(dy, dx) - finder heading)| <= fov / 2, it is not related to the
   finder (another tree of models), and a ray from the finder (its global pose + origin,
   turned by that bearing, range_max long) stops at it first: the ray stops at any block of
   a model not related to the finder whose height range holds the finder's height (sight.py);
   with ignore_zloc a ray that stops at nothing counts as stopping at the candidate;
4. a reading per kept candidate: range, bearing (relative to the finder's heading), geom =
   (his size x, y, z, normalize(his heading - the finder's)), pose = his global pose (Stage's
   pose_rel is commented out in 4.3.0: there is none), id = his fiducial_return if range <
   range_max_id else 0, and the model itself.
Poses are global poses (Model::GetGlobalPose: no `origin` offset) but for the ray's start.

What the world must provide (the lead's World.step wires it):
- one FiducialIndex(world.models), made after loading (Model::Load's SetFiducialReturn);
  .begin_step() at the start of every step, before any model's update (World::Update
  rebuilds its sets there); .set_return(model, value) is Model::SetFiducialReturn at run time;
- one sight.Sight(world.models, world.robots, world.space);
- per finder update: finder.update(index, sight, layer), layer = (world.updates + 1) % 2 as
  during a step's updates (what World::Raytrace reads). Stage skips the update of a finder
  without subscribers (its readings stay, it is not queued again); the caller decides that.
  Stage runs it in a worker thread (thread_safe), beside the moves: the poses it reads are
  those at the time of the call.
"""
import bisect
import math
from dataclasses import dataclass
from operator import attrgetter, itemgetter

import numpy as np

from . import models
from .jit import kernel
from .pose import pose_add, stage_normalize
from .sensing import update_all

DEFAULT_RANGE_MAX = 8.0          # max_range_anon, m
DEFAULT_RANGE_MAX_ID = 5.0       # max_range_id, m
DEFAULT_FOV = math.pi            # rad


@dataclass(frozen=True)
class FiducialReading:
    """One model seen, as Stage's ModelFiducial::Fiducial holds it."""

    model: object      # the model seen (Stage's `mod`)
    range: float       # m, from the finder's global position to his
    bearing: float     # rad, relative to the finder's heading, in [-fov/2, fov/2]
    geom: tuple        # (his size x, y, z in m, his heading relative to the finder's, rad)
    pose: tuple        # his global pose (x, y, z, a)
    id: int            # his fiducial_return, or 0 at range_max_id and beyond


def python_poses(models, body=False, at=None):
    """Model.global_pose (or body_pose) of each model, as an (n, 4) array (body: one for
    all, or one per model)."""
    each = np.broadcast_to(np.asarray(body, np.bool_), (len(models),)).tolist()
    return np.array([m.body_pose() if b else m.global_pose()
                     for m, b in zip(models, each, strict=True)], np.float64).reshape(-1, 4)


class FiducialIndex:
    """World::models_with_fiducials and its two sets sorted by x and by y.

    models: the world's models in load order; each with fiducial_return != 0 is inserted as
    Model::Load's SetFiducialReturn does. rank(model): its place in Stage's order of
    addresses (STAGE_MODEL_POINTER_ORDER), default its load index: give it the order a
    capture of real Stage printed to replay that run."""

    def __init__(self, models, rank=None):
        self.rank = rank if rank is not None else (lambda m: m.index)
        # poses(models, body=False, at=None): their global poses (or their bodies' frames;
        # body: one bool for all, or one per model) now, an (n, 4) array (at: their indices,
        # or None); the World gives its kernels' (World.global_poses)
        self.poses = python_poses
        self._constants = {}
        self._finder_row = {}
        self.finder_sets = {}       # finders.prepare_ids's plans per set of finders
        # changes with the members, their returns or anyone's key (set_return, set_key)
        self.version = 0
        self.steps = 0          # begin_step's count
        # whether a finder that reads its nearest only (Fiducial.nearest_only) may skip the
        # rays to the others (the World says no when your own controllers run)
        self.nearest_only_allowed = True
        self.finder_table = dict(ints=np.zeros((0, 4), np.int64),
                                 floats=np.zeros((0, 3), np.float64))
        self.models = []      # Stage's vector: insertion order (erase, then push_back)
        for m in models:
            self.set_return(m, m.fiducial_return)
        self._members = []
        self._members_of = None     # the version _members were taken at
        self._member_constants = (None, None)   # (_members, their constants)
        self._order_x = self._order_y = np.zeros(0, np.int64)
        self._sorted_for = None     # (the members' constants, their poses) last sorted
        self.begin_step()

    def set_return(self, model, value):
        """Model::SetFiducialReturn: the model's fiducial_return = value; a non-zero one joins
        the fiducial-bearing models (at the end), 0 leaves them. The finders' candidates
        follow at the next begin_step, as Stage's sets."""
        model.fiducial_return = int(value)
        self.version += 1
        if model in self.models:
            self.models.remove(model)
        if model.fiducial_return != 0:
            self.models.append(model)

    def set_key(self, model, value):
        """Model::SetFiducialKey."""
        model.fiducial_key = int(value)
        self.version += 1

    def begin_step(self):
        """World::Update's first work: the sets sorted by global x and by global y (ties by
        address: rank) rebuilt from the fiducial-bearing models' poses now."""
        self.steps += 1
        if self._members_of != self.version:
            self._members = list(self.models)
            self._members_of = self.version
        members = self._members
        constants = self.constants(members)
        _, at, self._ranks, _, _ = constants
        poses = self.poses(members, at=at)
        last = self._sorted_for
        if last is not None and last[0] is constants and np.array_equal(last[1], poses):
            return                  # the same models where they were: the same orders
        if last is not None and last[0] is constants:
            # the same models, moved a little: the last orders sorted again from where they
            # were (np.lexsort's orders, _resort), in few swaps
            self._order_x = self._order_x.copy()
            self._order_y = self._order_y.copy()
            _resort(self._order_x, poses, 0, self._ranks)
            _resort(self._order_y, poses, 1, self._ranks)
        else:
            self._order_x = np.lexsort((self._ranks, poses[:, 0]))
            self._order_y = np.lexsort((self._ranks, poses[:, 1]))
        self._sorted_for = (constants, poses)

    def constants(self, models):
        """(root indices, model indices, ranks, the models' places by rank, each model's
        place among those) of the models, arrays, kept for the same list of models (the
        sets' members from one begin_step to the next)."""
        if models is self._member_constants[0]:     # the sets' members: asked every step
            return self._member_constants[1]
        key = (self.rank, tuple(models))
        got = self._constants.get(key)
        if got is None:
            if len(self._constants) > 8:
                self._constants.clear()
            ranks = np.array([self.rank(h) for h in models], np.float64)
            by_rank = np.argsort(ranks, kind='stable')
            rank_at = np.empty(len(models), np.int64)
            rank_at[by_rank] = np.arange(len(models))
            got = self._constants[key] = (
                np.array([h.root.index for h in models], np.int64),
                np.array([h.index for h in models], np.int64), ranks, by_rank, rank_at)
        if models is self._members:
            self._member_constants = (models, got)
        return got

    def finder_rows(self, finders, sight):
        """Each finder's row in finder_table ('ints': root index, ignore_zloc, the tree
        sight's static tables know it by, model index; 'floats': range_max, range_max_id,
        fov: what a finder does not change once loaded), added the first time it is seen."""
        row = self._finder_row
        new = [f for f in finders if f not in row]
        if new:
            table = self.finder_table
            for f in new:
                row[f] = len(row)
            root = [f.root.index for f in new]
            table['ints'] = np.concatenate((table['ints'], np.array(
                [(r, int(f.ignore_zloc), sight.tree_key(r), f.index)
                 for f, r in zip(new, root, strict=True)], np.int64)))
            table['floats'] = np.concatenate((table['floats'], np.array(
                [(f.range_max, f.range_max_id, f.fov) for f in new], np.float64)))
        return np.fromiter((row[f] for f in finders), np.int64, len(finders))

    def nearby(self, x, y, rng):
        """The candidates of a finder at global (x, y) with range rng, in Stage's order
        (STAGE_FIDUCIAL_BOX, STAGE_MODEL_POINTER_ORDER in the module docstring)."""
        members = self._members
        horiz = _above([members[k] for k in self._order_x.tolist()], 0, x - rng, x + rng)
        vert = _above([members[k] for k in self._order_y.tolist()], 1, y - rng, y + rng)
        return sorted(horiz & vert, key=self.rank)


@kernel
def _resort(order, poses, axis, ranks):
    """order (the models' places) sorted in place by (poses[., axis], ranks[.], place) by
    insertion from where it is: np.lexsort((ranks, poses[:, axis])) (a stable sort: the
    place last), in a few swaps when the models moved little."""
    for i in range(1, order.shape[0]):
        v = order[i]
        key = poses[v, axis]
        rank = ranks[v]
        j = i - 1
        while j >= 0:
            u = order[j]
            if poses[u, axis] < key or (poses[u, axis] == key and (
                    ranks[u] < rank or (ranks[u] == rank and u < v))):
                break
            order[j + 1] = u
            j -= 1
        order[j + 1] = v


def _above(ordered, axis, lo, hi):
    """The models of `ordered` between lower_bound(lo) and upper_bound(hi) of a std::set
    sorted on that axis, bounded by a model ranking above every other at equal coordinates:
    both bounds are the first model whose coordinate (its global pose now, as Stage's
    comparisons read it) is above the bound."""
    keys = _LiveKeys(ordered, axis)
    start = bisect.bisect_right(keys, lo)
    end = bisect.bisect_right(keys, hi)
    return set(ordered[start:end])


class _LiveKeys:
    """A sequence of the models' global coordinates, read when the search asks."""

    def __init__(self, ordered, axis):
        self.ordered = ordered
        self.axis = axis

    def __len__(self):
        return len(self.ordered)

    def __getitem__(self, k):
        return self.ordered[k].global_pose()[self.axis]


class Fiducial(models.Fiducial):
    """ModelFiducial: its properties and its readings (`fiducials`, Stage's order)."""

    thread_safe = True       # Stage updates it in a worker thread, beside the moves

    def construct(self):
        super().construct()
        self.range_min = 0.0
        self.range_max = DEFAULT_RANGE_MAX
        self.range_max_id = DEFAULT_RANGE_MAX_ID
        self.fov = DEFAULT_FOV
        self.ignore_zloc = False
        # only nearest() is read (its controller says so): an update may find the nearest
        # alone, the readings completed if asked in the same step (finders._Seen.complete)
        self.nearest_only = False
        self._fiducials = []
        # (update_all's _Seen, this finder's place in it) while the readings are not made
        self._seen = None

    def load(self, wf, rand48):
        """ModelFiducial::Load: Model::Load, then the finder's own properties."""
        super().load(wf, rand48)
        e = self.entity
        self.range_min = wf.read_length(e, 'range_min', self.range_min)
        self.range_max = wf.read_length(e, 'range_max', self.range_max)
        self.range_max_id = wf.read_length(e, 'range_max_id', self.range_max_id)
        self.fov = wf.read_angle(e, 'fov', self.fov)
        self.ignore_zloc = wf.read_int(e, 'ignore_zloc', int(self.ignore_zloc)) != 0

    def related(self, other):
        """Model::IsRelated: the same tree of models."""
        return self.root is other.root

    def update(self, index, sight, layer):
        """ModelFiducial::Update: the readings (self.fiducials, also returned) of the
        candidates index offers, rays through the grid's `layer`."""
        update_all([self], index, sight, layer)
        return self.fiducials

    def update_one_by_one(self, index, sight, layer):
        """update(), candidate by candidate in Python (sees(): the rule as written)."""
        gx, gy, _, _ = self.global_pose()
        self.fiducials = []
        for him in index.nearby(gx, gy, self.range_max):
            reading = self.sees(him, sight, layer)
            if reading is not None:
                self.fiducials.append(reading)
        return self.fiducials

    @property
    def fiducials(self):
        """What the last update saw (FiducialReadings, Stage's order); made from the
        kernel's numbers when first asked."""
        if self._seen is not None:
            step, i = self._seen
            if step.count[i] < 0:
                step.complete(i)
            members, poses, (out_c, out_f, out_id) = step.members, step.poses, step.out
            at, count = i * len(members), int(step.count[i])
            self._seen = None
            if not count:                   # most updates see nothing
                self._fiducials = []
                return self._fiducials
            end = at + count
            self._fiducials = [
                _reading(members[c], poses[c].tolist(), rng, bearing, geom_a, fid)
                for c, (rng, bearing, geom_a), fid in zip(
                    out_c[at:end].tolist(), out_f[at:end].tolist(), out_id[at:end].tolist(),
                    strict=True)]
        return self._fiducials

    @fiducials.setter
    def fiducials(self, value):
        self._fiducials = value
        self._seen = None

    def seen_count(self):
        """How many readings the last update made, without making them."""
        if self._seen is not None:
            step, i = self._seen
            if step.count[i] < 0:
                step.complete(i)
            return int(step.count[i])
        return len(self._fiducials)

    def nearest(self):
        """(range, his heading relative to the finder's) of the first reading of the least
        range, or None (what pioneer_flocking takes of the last update)."""
        if self._seen is not None:
            step, i = self._seen
            near = step.nearest[i]
            return (float(near[0]), float(near[1])) if near[2] else None
        best = None
        for seen in self._fiducials:
            if seen.range < (best.range if best is not None else 1e6):
                best = seen
        return None if best is None else (best.range, best.geom[3])

    def sees(self, him, sight, layer):
        """AddModelIfVisible: the reading of `him`, or None."""
        if self.fiducial_key != him.fiducial_key:
            return None
        mx, my, _, ma = self.global_pose()
        hispose = him.global_pose()
        dx = hispose[0] - mx
        dy = hispose[1] - my
        rng = float(np.hypot(dy, dx))        # the C library's hypot, as Stage's
        if rng >= self.range_max:
            return None
        dtheta = stage_normalize(math.atan2(dy, dx) - ma)
        if abs(dtheta) > self.fov / 2.0:
            return None
        if self.related(him):
            return None
        origin = pose_add(self.body_pose(), (0.0, 0.0, 0.0, dtheta))
        _, hit = sight.cast(origin, [origin[3]], self.range_max, self, True, layer)
        hit = int(hit[0])
        if self.ignore_zloc and hit < 0:
            hit = him.index
        if hit != him.index:
            return None
        size = him.geom_size
        return FiducialReading(
            model=him, range=rng, bearing=dtheta,
            geom=(size[0], size[1], size[2], stage_normalize(hispose[3] - ma)),
            pose=hispose, id=him.fiducial_return if rng < self.range_max_id else 0)


def last_nearest_of(finders):
    """Fiducial.nearest() of each finder as an array of rows (range, his heading relative to
    the finder's, 1.0 if it saw one else 0.0), when one update_all made their readings and
    none were made or replaced since; else None."""
    seen = list(map(_SEEN, finders))
    try:
        steps = set(map(_STEP, seen))
    except TypeError:           # one's readings made or set (its _seen None)
        return None
    if len(steps) != 1:
        return None
    return steps.pop().nearest[np.fromiter(map(_ROW, seen), np.int64, len(seen))]


_SEEN = attrgetter('_seen')
_STEP = itemgetter(0)
_ROW = itemgetter(1)


def _reading(him, hispose, rng, bearing, geom_a, fid):
    size = him.geom_size
    return FiducialReading(model=him, range=rng, bearing=bearing,
                           geom=(size[0], size[1], size[2], geom_a), pose=tuple(hispose),
                           id=fid)
