"""Stage 4.3's energy model (libstage/powerpack.cc, model.cc): power packs, what models
draw from them, and chargers that fill the packs of the models touching them (no rospy).

A model gets a power pack from its world-file properties, read in Stage's order:
`joules J` (stored = capacity = J; a negative J is an infinite supply), `joules_capacity`,
`kjoules K` (stored = capacity = 1000 K), `kjoules_capacity` (1000 K); a later one overrides
an earlier one, and a capacity below the store cuts the store. Every model also reads
`watts` (what it dissipates), `give_watts` (a charger's rate), `take_watts` (the most a
model takes from a charger) and `mass` (kg). A model without a pack draws from its
nearest ancestor's (FindPowerPack).

A model joins the world's energy set when it starts (its first subscription, or `alwayson`)
and has a pack somewhere up its tree, and leaves it at its shutdown. Its watts change as
Stage's types set them: a ranger draws 0.2 W per sensor while started, a blobfinder 2 W, a
bumper 0.1 W (the world file's `watts` is then overwritten); a position model, at each of
its updates while subscribed, 1 W + 10 W per kg per unit of speed, times (|vx| + |vy| + |va|)
of the velocity it was commanded, before velocity_bounds clip it.

At the end of each step (after the world's callbacks) each model of the set, in Stage's model
order, dissipates watts x interval_energy (0.1 s, whatever interval_sim is: with a 20 ms step
a pack runs down five times faster than its watts say) from its pack, and a model with
give_watts hands min(give_watts, his take_watts) x interval_energy to each model that touches
it and has take_watts and a pack: touching as Stage's AppendTouchingModels finds it, a model
with a block in a cell the charger's own blocks are drawn into, in the layer this step's moves
drew (no height test; models of the charger's own tree are not counted). An empty pack stays
at 0 and nothing else happens: Stage 4.3 stops no model for lack of energy.
"""
from operator import attrgetter

import numpy as np

from .grid import RBITS, REGION, region_index
from .jit import kernel, njit, unsigned

ENERGY_INTERVAL_US = 100000          # Model::interval_energy, fixed in Stage 4.3
POSITION_WATTS = 1.0                 # ModelPosition's base draw
POSITION_WATTS_KGMS = 10.0           # per kg per m/s (and per rad/s)
RANGER_WATTS_PER_SENSOR = 0.2
BLOBFINDER_WATTS = 2.0
BUMPER_WATTS = 0.1
#: what each kind draws while started (Startup's SetWatts; Shutdown sets 0)
STARTED_WATTS = {'blobfinder': BLOBFINDER_WATTS, 'bumper': BUMPER_WATTS}
#: a power pack's columns in its table
STORED, CAPACITY, DISSIPATED, SUPPLIED = range(4)


def _column(k, doc):
    """A PowerPack's number held in column k of its table's row."""
    def get(self):
        return float(self._values[self._row, k])

    def put(self, value):
        self._values[self._row, k] = value
    return property(get, put, doc=doc)


class PowerPack:
    """Stage's PowerPack: joules stored (negative: an infinite supply), capacity, whether it
    is being charged, and what it has dissipated; `supplied`, what an infinite supply gave.

    Its numbers live in a row of a table (its own, until the world's energy set takes it
    into the set's table: Energy._adopt), so that a step's dissipations are one kernel's."""

    __slots__ = ('_values', '_charging', '_row')

    def __init__(self, stored=0.0, capacity=0.0):
        self._values = np.array([[float(stored), float(capacity), 0.0, 0.0]], np.float64)
        self._charging = np.zeros(1, np.bool_)
        self._row = 0

    stored = _column(STORED, 'joules stored (negative: an infinite supply)')
    capacity = _column(CAPACITY, 'joules it holds at most')
    dissipated = _column(DISSIPATED, 'joules lost as work or heat')
    supplied = _column(SUPPLIED, 'joules an infinite supply gave')

    @property
    def charging(self):
        return bool(self._charging[self._row])

    @charging.setter
    def charging(self, value):
        self._charging[self._row] = value

    def move_to(self, values, charging, row):
        """Its numbers copied into row `row` of the tables values and charging, and kept
        there from now on."""
        values[row] = self._values[self._row]
        charging[row] = self._charging[self._row]
        self._values, self._charging, self._row = values, charging, row

    def __repr__(self):
        return 'PowerPack(%.2f / %.2f J)' % (self.stored, self.capacity)

    def remaining_capacity(self):
        return self.capacity - self.stored

    def proportion_remaining(self):
        """stored / capacity (Stage divides as it is: a pack of capacity 0 gives inf or nan)."""
        if self.capacity == 0.0:
            return float('nan') if self.stored == 0.0 else float('inf') * np.sign(self.stored)
        return self.stored / self.capacity

    def set_capacity(self, joules):
        self.capacity = float(joules)
        if self.stored > self.capacity:
            self.stored = self.capacity

    def set_stored(self, joules):
        self.stored = float(joules)

    def add(self, joules):
        """Adds up to the remaining capacity; any gain marks it charging."""
        amount = min(self.remaining_capacity(), joules)
        self.stored += amount
        if amount > 0:
            self.charging = True

    def subtract(self, joules):
        """Takes up to what is stored; an infinite supply gives it all and keeps its store."""
        if self.stored < 0:
            self.supplied += joules
            return
        self.stored -= min(self.stored, joules)

    def transfer_to(self, dest, joules):
        """Moves up to `joules` (no more than stored, unless infinite, nor than dest can
        take) from this pack to dest."""
        amount = joules
        if self.stored >= 0.0:
            amount = min(self.stored, amount)
        amount = min(amount, dest.remaining_capacity())
        self.subtract(amount)
        dest.add(amount)

    def dissipate(self, joules):
        """Loses energy as work or heat: all of it from an infinite supply, else no more than
        is stored (the step's own rule, _dissipate, on this pack's row)."""
        _dissipate(np.array([self._row], np.int64), np.array([float(joules)]), 0, 1,
                   self._values, 1.0)


def load_energy(model, wf, entity):
    """Model::Load's energy properties, in its order, onto model (power_pack, watts,
    watts_give, watts_take, mass)."""
    def pack():
        if model.power_pack is None:
            model.power_pack = PowerPack()
        return model.power_pack

    if wf.exists(entity, 'joules'):
        p = pack()
        j = wf.read_float(entity, 'joules', p.stored)
        p.set_stored(j)
        p.set_capacity(j)
    if wf.exists(entity, 'joules_capacity'):
        p = pack()
        p.set_capacity(wf.read_float(entity, 'joules_capacity', p.capacity))
    if wf.exists(entity, 'kjoules'):
        p = pack()
        j = 1000.0 * wf.read_float(entity, 'kjoules', p.stored)
        p.set_stored(j)
        p.set_capacity(j)
    if wf.exists(entity, 'kjoules_capacity'):
        p = pack()
        p.set_capacity(1000.0 * wf.read_float(entity, 'kjoules_capacity', p.capacity))
    model.watts = wf.read_float(entity, 'watts', model.watts)
    model.watts_give = wf.read_float(entity, 'give_watts', model.watts_give)
    model.watts_take = wf.read_float(entity, 'take_watts', model.watts_take)
    model.mass = wf.read_float(entity, 'mass', model.mass)


def find_power_pack(model):
    """Model::FindPowerPack: the model's pack, or its nearest ancestor's, or None."""
    m = model
    while m is not None:
        if m.power_pack is not None:
            return m.power_pack
        m = m.parent
    return None


def position_watts(mass, velocity):
    """What a position model draws at the velocity it was commanded (x, y, z, a)."""
    vx, vy, _, va = velocity
    return POSITION_WATTS + (abs(vx) + abs(vy) + abs(va)) * POSITION_WATTS_KGMS * mass


class Energy:
    """A world's energy set and its per-step charge update.

    world: what it reads, `space`, `models`, `updates`, `ppm`, `robot_of(model)`, and the
    rank of each model in Stage's order (`rank`, a function)."""

    def __init__(self, world, rank):
        self.world = world
        self.rank = rank
        self.active = set()           # Stage's World::active_energy
        self._order = []              # (model, its pack) of the set, in Stage's order
        self._charging = {}           # charger -> the packs it charged at its last update
        self._static_cells = {}       # a static charger or taker -> its cells
        self._static_takers = None
        self._quiet = None            # the static chargers' cells at once (_quiet_chargers)
        # the set's packs in one table, each model's row and which are chargers, made at the
        # first update after the set changed (_adopt)
        self._table = None

    # ---- the models' lives (Model::Startup / Shutdown) -------------------------------------
    def has_packs(self):
        """Whether any model has a power pack (else nothing here ever does anything)."""
        return any(getattr(m, 'power_pack', None) is not None for m in self.world.models)

    def started(self, model):
        if find_power_pack(model) is not None:
            self._enable(model)
        if model.kind == 'ranger':
            model.watts = RANGER_WATTS_PER_SENSOR * len(model.sensors)
        elif model.kind in STARTED_WATTS:
            model.watts = STARTED_WATTS[model.kind]

    def stopped(self, model):
        if model.kind == 'ranger' or model.kind in STARTED_WATTS:
            model.watts = 0.0
        if model in self.active:
            self.active.discard(model)
            self._sort()

    def _enable(self, model):
        if model not in self.active:
            self.active.add(model)
            self._sort()

    def _sort(self):
        """The set in Stage's order, each model with its pack (packs are made with their
        models, at load: found once)."""
        self._order = [(m, find_power_pack(m)) for m in sorted(self.active, key=self.rank)]
        self._quiet = None
        self._table = None

    def _adopt(self):
        """The set's packs moved into one table (each once, in the set's order), with each
        model's row in it, and the places of the models that give (watts_give, read at
        load)."""
        packs = list({id(p): p for _, p in self._order}.values())
        values = np.zeros((len(packs), 4), np.float64)
        charging = np.zeros(len(packs), np.bool_)
        row = {}
        for k, p in enumerate(packs):
            p.move_to(values, charging, k)
            row[id(p)] = k
        models = [m for m, _ in self._order]
        self._table = (values, models,
                       np.array([row[id(p)] for _, p in self._order], np.int64),
                       [k for k, m in enumerate(models) if m.watts_give > 0])

    def statics_moved(self):
        """A static model was moved, resized or made (runtime_models): the static chargers'
        and takers' cells found again when next needed."""
        self._static_cells.clear()
        self._static_takers = None
        self._quiet = None

    def position_updated(self, model, velocity):
        """ModelPosition::Update's power draw, from the velocity before its bounds."""
        model.watts = position_watts(model.mass, velocity)

    # ---- World::Update's last part ---------------------------------------------------------
    def update(self):
        """Model::UpdateCharge of every model of the set, in Stage's order: the
        dissipations in a kernel, stopped at each charger that may give or has charged
        something (its part in Python, _give); a quiet charger that charged nothing last
        step would only note that it charges nothing."""
        quiet = self._quiet_chargers()
        if self._table is None:
            self._adopt()
        values, models, rows, givers = self._table
        watts = np.fromiter(map(_WATTS, models), np.float64, len(models))
        start = 0
        for k in givers:
            model, pack = self._order[k]
            if model not in quiet or self._charging.get(model):
                # a charger that may give, or stop charging what it charged: its own
                # dissipation and those before it first, then its part in Python
                _dissipate(rows, watts, start, k + 1, values, ENERGY_INTERVAL_US * 1e-6)
                start = k + 1
                self._give(model, pack, model in quiet)
        _dissipate(rows, watts, start, len(models), values, ENERGY_INTERVAL_US * 1e-6)

    def _give(self, model, pack, quiet):
        """A charger's part of UpdateCharge: to every model touching it that takes (none
        when it is `quiet`: see _quiet_chargers)."""
        for p in self._charging.pop(model, ()):
            p.charging = False
        charged = []
        for toucher in () if quiet else self.touching(model):
            his = find_power_pack(toucher)
            if his is not None and toucher.watts_take > 0.0:
                rate = min(model.watts_give, toucher.watts_take)
                his.charging = True
                pack.transfer_to(his, rate * ENERGY_INTERVAL_US * 1e-6)
                charged.append(his)
        self._charging[model] = charged

    # ---- Block::AppendTouchingModels -------------------------------------------------------
    def touching(self, model):
        """The models, in Stage's order, with a block in a cell one of `model`'s own blocks is
        drawn into in this step's layer, but those of model's own tree."""
        world = self.world
        space = world.space
        layer = world.updates % 2
        xs, ys = self._cells_of(model, layer)
        found = set()
        if xs.size:
            self._dynamic_in(space, xs, ys, layer, found)
            for other, (ox, oy) in self._takers().items():
                if _share_cell(xs, ys, ox, oy):
                    found.add(other.index)
        root = model.root
        models = world.models
        return sorted((models[i] for i in found if models[i].root is not root), key=self.rank)

    def _cells_of(self, model, layer):
        """The cells the model's blocks are drawn into: from the grid for a moving model,
        from its outline once for a static one."""
        world = self.world
        robot = world.robot_of(model.root)
        if robot is None:
            cells = self._static_cells.get(model)
            if cells is None:
                cells = self._static_cells[model] = outline_cells(model, world.ppm)
            return cells
        space = world.space
        ks = [k for m, ids in robot.blocks if m is model for k in ids]
        xs = [space.rc_x[layer, space.rc_start[k]:space.rc_start[k] + space.rc_len[layer, k]]
              for k in ks]
        ys = [space.rc_y[layer, space.rc_start[k]:space.rc_start[k] + space.rc_len[layer, k]]
              for k in ks]
        if not xs:
            return np.zeros(0, np.int64), np.zeros(0, np.int64)
        return np.concatenate(xs), np.concatenate(ys)

    @staticmethod
    def _dynamic_in(space, xs, ys, layer, found):
        """Adds the model index of every moving block listed in the cells (xs, ys)."""
        found.update(_dynamic_models(xs, ys, layer, space.rx0, space.ry0, space.nrx,
                                     space.nry, space.reg_dyn, space.dyn_head,
                                     space.ent_block, space.ent_next,
                                     space.blk_model).tolist())

    def _quiet_chargers(self):
        """The static chargers of the set that touch nothing this step: no moving block
        drawn in their cells in this step's layer (one kernel for them all: most steps, no
        robot is at a charger) and no static taker sharing a cell. touching() would find
        nobody for them."""
        if self._quiet is None:
            world = self.world
            chargers, cells = [], []
            for m, _ in self._order:
                if m.watts_give > 0 and world.robot_of(m.root) is None:
                    xs, ys = self._cells_of(m, 0)
                    if not any(_share_cell(xs, ys, ox, oy) for ox, oy in self._takers().values()):
                        chargers.append(m)
                        cells.append((xs, ys))
            offsets = np.cumsum([0] + [len(xs) for xs, _ in cells]).astype(np.int64)
            xs = np.concatenate([c[0] for c in cells] + [np.zeros(0, np.int64)])
            ys = np.concatenate([c[1] for c in cells] + [np.zeros(0, np.int64)])
            self._quiet = (chargers, xs, ys, offsets, np.zeros(len(chargers), np.bool_))
        chargers, xs, ys, offsets, busy = self._quiet
        if not chargers:
            return ()
        space = self.world.space
        _cells_hold_moving(xs, ys, offsets, self.world.updates % 2, space.rx0, space.ry0,
                           space.nrx, space.nry, space.reg_dyn, space.dyn_head, busy)
        return {m for m, b in zip(chargers, busy.tolist(), strict=True) if not b}

    def _takers(self):
        """The static models that could take a charge (take_watts and a pack), with their
        cells: a charger touching a wall gives it nothing, so only these are looked at."""
        if self._static_takers is None:
            world = self.world
            self._static_takers = {
                m: outline_cells(m, world.ppm) for m in world.models
                if world.robot_of(m.root) is None and m.watts_take > 0
                and find_power_pack(m) is not None}
        return self._static_takers


def outline_cells(model, ppm):
    """(x, y) cells of a model's blocks' outlines at its pose now (Stage's MapPoly)."""
    cells = [model.outline_cells(block, ppm) for block in model.blocks]
    xs, ys = [c[0] for c in cells], [c[1] for c in cells]
    if not xs:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    return np.concatenate(xs), np.concatenate(ys)


_WATTS = attrgetter('watts')


@kernel
def _dissipate(rows, watts, start, end, values, seconds):
    """PowerPack.dissipate(watts x seconds) of the models start..end-1 of the set, in turn,
    each on its pack's row of values (only those with watts above 0)."""
    for k in range(start, end):
        w = watts[k]
        if w > 0:
            r = rows[k]
            joules = w * seconds
            stored = values[r, STORED]
            if stored < 0:                      # an infinite supply gives it all
                values[r, SUPPLIED] += joules
                values[r, DISSIPATED] += joules
            else:
                amount = min(stored, joules)
                values[r, STORED] = stored - amount
                values[r, DISSIPATED] += amount


def _share_cell(xs, ys, ox, oy):
    a = set(zip(xs.tolist(), ys.tolist(), strict=True))
    return any(c in a for c in zip(ox.tolist(), oy.tolist(), strict=True))


@njit(cache=True)
def _dynamic_models(xs, ys, layer, rx0, ry0, nrx, nry, reg_dyn, dyn_head, ent_block, ent_next,
                    blk_model):
    """The model of each moving block listed in the cells (xs, ys) of `layer` (repeats
    included), the grid's pages walked as Space's kernels walk them."""
    out = np.empty(64, np.int64)
    n = 0
    for k in range(xs.size):
        x, y = xs[k], ys[k]
        tx = (x >> RBITS) - rx0
        ty = (y >> RBITS) - ry0
        if tx < 0 or ty < 0 or tx >= nrx or ty >= nry:
            continue
        page = reg_dyn[ty * nrx + tx]
        if page < 0:
            continue
        e = dyn_head[page, layer, (y & (REGION - 1)) * REGION + (x & (REGION - 1))]
        while e >= 0:
            if n == out.size:
                grown = np.empty(2 * n, np.int64)
                grown[:n] = out
                out = grown
            out[n] = blk_model[ent_block[e]]
            n += 1
            e = ent_next[e]
    return out[:n]


@kernel
def _cells_hold_moving(xs, ys, offsets, layer, rx0, ry0, nrx, nry, reg_dyn, dyn_head, out):
    """out[g]: whether any of the cells (xs, ys)[offsets[g]:offsets[g + 1]] holds a moving
    block in `layer` (the grid's pages walked as Space's kernels walk them)."""
    for g in range(offsets.shape[0] - 1):
        out[g] = False
        for k in range(offsets[g], offsets[g + 1]):
            x = xs[k]
            y = ys[k]
            reg = region_index(x, y, rx0, ry0, nrx, nry)
            if reg < 0:
                continue
            page = reg_dyn[unsigned(reg)]
            if page < 0:
                continue
            cell = (y & (REGION - 1)) * REGION + (x & (REGION - 1))
            if dyn_head[unsigned(page), unsigned(layer), unsigned(cell)] >= 0:
                out[g] = True
                break
