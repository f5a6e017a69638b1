"""What fasr2's robots share (Stage's statics in examples/ctrl/fasr2.cc): the tasks, the
planner's grid and the plans, each plan a path of cell centres that advises a heading (its
Graph::GoodDirection). Not a controller itself (no init); fasr2.py says the rules.
"""
import math

import numpy as np

from stage_lite.model.jit import kernel
from stage_lite.model.stage_api import normalize

from ._astar import BLOCKED, astar

MAP_CELLS = 32            # the planner's grid, each way
MAP_MODEL = 'cave'
ADVICE_RANGE = 5.0        # m: plan nodes farther away give no advice
LANE_BIAS = 0.25          # rad to the left of the best node


def meters_to_cell(m, size_m, cells):
    """fasr2's MetersToCell: shifted by half the size, scaled, floored."""
    return math.floor((m + size_m / 2.0) / (size_m / float(cells)))


def cell_to_meters(c, size_m, cells):
    """fasr2's CellToMeters: the centre of cell c."""
    cell = size_m / float(cells)
    return c * cell - size_m / 2.0 + cell / 2.0


def cost_grid(raster):
    """The planner's costs from a raster: 0 (free) -> 1, 1 (an outline) -> 9."""
    grid = np.frombuffer(bytes(raster), np.uint8)
    return np.where(grid == 0, 1, BLOCKED).astype(np.uint8)


class Task:
    def __init__(self, source, sink):
        self.source = source
        self.sink = sink
        self.participants = 0


def reach(model):
    """How near a source or sink a robot must be to be at it (fasr2: half its width)."""
    return model.get_geom()[1][0] / 2.0


class Plan:
    """A planned path: its nodes' centres (goal first, so a node's index is its value, the
    steps from it to the goal); `id`: its number among its Shared's plans (-1 alone)."""

    def __init__(self, xs, ys, plan_id=-1):
        self.xs = np.asarray(xs, np.float64)
        self.ys = np.asarray(ys, np.float64)
        self.id = plan_id

    def good_direction(self, x, y, within=ADVICE_RANGE):
        """Graph::GoodDirection: the heading to the best node in range, plus the lane bias;
        None for no advice."""
        best = best_node(self.xs, self.ys, 0, self.xs.shape[0], x, y, within)
        if best < 0:
            return None
        return normalize(math.atan2(self.ys[best] - y, self.xs[best] - x) + LANE_BIAS)


@kernel
def best_node(xs, ys, start, end, x, y, within):
    """The first node of xs[start:end] within range (values rise with the index: the first
    has the least), its place in xs; -1 for none."""
    for i in range(start, end):
        if math.hypot(xs[i] - x, ys[i] - y) < within:
            return i
    return -1


class Shared:
    """What fasr2's robots share (Stage's statics): the tasks, the grid and the plans."""

    def __init__(self, world, colours):
        if not colours:
            raise ValueError('fasr2 needs at least one task colour: ctrl "fasr2 red green ..."')
        world.srandom(world.clock_seed if world.clock_seed is not None else 1)
        self.tasks = []
        for colour in colours:
            ends = []
            for end in ('_source', '_sink'):
                ends.append(world.get_model(colour + end))
                if ends[-1] is None:
                    raise LookupError('fasr2\'s task "%s" needs a model named "%s%s"'
                                      % (colour, colour, end))
            self.tasks.append(Task(*ends))
        cave = world.get_model(MAP_MODEL)
        if cave is None:
            raise LookupError('fasr2 plans on a model named "%s": there is none' % MAP_MODEL)
        _, size = cave.get_geom()
        self.size = size
        self.costs = cost_grid(cave.rasterize(MAP_CELLS, MAP_CELLS, size[0] / float(MAP_CELLS),
                                              size[1] / float(MAP_CELLS)))
        self.plans = {}
        self.misses = 0
        # every plan's nodes one after the other (plan k's from _node_off[k]), for the
        # batch's kernel; the arrays grow by doubling
        self._node_xs = np.zeros(64)
        self._node_ys = np.zeros(64)
        self._node_off = np.zeros(65, np.int64)

    def cell(self, pose):
        return (meters_to_cell(pose.x, self.size[0], MAP_CELLS),
                meters_to_cell(pose.y, self.size[1], MAP_CELLS))

    def plan(self, start, goal):
        """The plan from cell start to cell goal, planned at its first asking."""
        key = (start, goal)
        plan = self.plans.get(key)
        if plan is None:
            self.misses += 1
            path = astar(self.costs, MAP_CELLS, MAP_CELLS, start, goal)[::-1]
            plan = self.plans[key] = Plan(
                [cell_to_meters(c[0], self.size[0], MAP_CELLS) for c in path],
                [cell_to_meters(c[1], self.size[1], MAP_CELLS) for c in path],
                len(self.plans))
            self._keep_nodes(plan)
        return plan

    def _keep_nodes(self, plan):
        k = plan.id
        start = int(self._node_off[k])
        end = start + plan.xs.shape[0]
        if end > self._node_xs.shape[0]:
            size = max(end, 2 * self._node_xs.shape[0])
            self._node_xs = np.resize(self._node_xs, size)
            self._node_ys = np.resize(self._node_ys, size)
        if k + 2 > self._node_off.shape[0]:
            self._node_off = np.resize(self._node_off, 2 * self._node_off.shape[0])
        self._node_xs[start:end] = plan.xs
        self._node_ys[start:end] = plan.ys
        self._node_off[k + 1] = end

    def plan_nodes(self):
        """(xs, ys, off): every plan's nodes, plan k's at [off[k]:off[k + 1]]."""
        return self._node_xs, self._node_ys, self._node_off
