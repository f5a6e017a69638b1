"""fasr's laser and finder updates, robot after robot, in one batch (scheduler.py's batch
protocol): the laser updates in one kernel.

Most of fasr's laser updates are one case: a working robot that is not hungry. It either
avoids (a new avoid drawing its count from random()'s stream, glibc_random.random_next) or
cruises and turns to the heading its cell's table gives (HAVE carrying a flag, NEED
without). The kernel does exactly that case, rule for rule as fasr.py (the same comparisons
and truncations, Stage's normalize, the tables' headings converted by math.radians), and
stops at the first robot in any other case (docking, undocking, hungry, a pose or a turn
that is not finite): that robot's update runs in Python, and the kernel goes on after it.

What the kernel reads of each robot's Python state (mode, avoid count, hunger, whether it
carries a flag) is gathered at the step's first batch run: the position updates, which move
the flags, come before every laser update (queue 0's callbacks first), the packs drain after
the callbacks, and a laser update changes only its own robot's mode and avoid count.

The finders' updates come between the lasers' (both in the worker queues). One that saw
nothing does only `charger_ahoy = False`, which the batch sets itself (the kernel's case
never reads it); one that saw something runs in Python.
"""
import math

import numpy as np

from stage_lite.model.jit import kernel
from stage_lite.model.motion import normalize

from ._avoid import VELOCITY, avoid_step_in_kernel, laser_rows


class FasrBatch:
    """fasr's Forager.laser_update and fiducial_update in turn, the lasers' in one kernel
    where the case allows (see the module)."""

    def __init__(self, rules):
        self.rules = rules          # fasr's constants, as a dict (fasr.py gives them)

    def prepare(self, entries):
        """The robots' fixed tables, or None when they do not share the world's arrays."""
        robots = [callback.function.__self__ for callback, _, _ in entries]
        # per entry: the finder (a finder's update), or None (a laser's)
        finders = [callback.handle if callback.function.__func__ is self.rules['finder_update']
                   else None for callback, _, _ in entries]
        n = len(robots)
        plan = dict(robots=robots, finders=finders, step=None, first=np.zeros(n, np.int64),
                    samples=np.zeros(n, np.int64), row=np.zeros(n, np.int64))
        arrays = None
        for i, r in enumerate(robots):
            if finders[i] is not None:
                continue
            sensor = r.laser.sensors[0]
            found = laser_rows(r.pos, sensor, arrays)
            if found is None:
                return None
            arrays, plan['first'][i], plan['row'][i] = found
            plan['samples'][i] = len(sensor.ranges)
        if arrays is None:
            return None
        plan['beams'], plan['goal'], plan['mode'], plan['pose'] = arrays
        if any(r.pack is None for r in robots):
            return None                 # hungry() fails in Python, where its error is told
        plan['world'] = robots[0].pos.world
        plan['random'] = plan['world'].random_stream()
        rules = self.rules
        # [carrying][row][column], in radians as heading_goal converts them
        plan['headings'] = np.array([[[math.radians(d) for d in line] for line in table]
                                     for table in (rules['need'], rules['have'])],
                                    np.float64)
        return plan

    def run(self, plan, rows):
        robots, finders = plan['robots'], plan['finders']
        now = plan['world'].sim_time_now()
        if plan['step'] != now:
            self._gather(plan)
            plan['step'] = now
        order = rows.tolist()
        n = len(order)
        j = 0
        while j < n:
            i = order[j]
            if finders[i] is not None:          # a finder's update
                if finders[i].seen_count():
                    return j                    # what it saw: its update in Python
                robots[i].charger_ahoy = False  # all it does when it saw nothing
                j += 1
                continue
            k = j + 1                           # the lasers' run from j
            while k < n and finders[order[k]] is None:
                k += 1
            done = self._lasers(plan, rows[j:k])
            j += done
            if j < k:
                return j
        return n

    def _lasers(self, plan, rows):
        """The laser updates `rows` in the kernel while each is its case: how many."""
        state = plan['state']
        rules = self.rules
        stream = plan['random']
        done = _work_all(rows, state['simple'], state['avoid'], state['carrying'],
                         plan['headings'], plan['beams'], plan['first'], plan['samples'],
                         plan['pose'], plan['row'], plan['goal'], plan['mode'], stream.table,
                         stream.pointers, rules['front'], rules['stop'],
                         rules['avoid_speed'], rules['avoid_turn'], rules['avoid_duration'],
                         rules['cruise'], rules['cell_origin'], rules['cell_size'],
                         rules['cells'])
        avoid = state['avoid']
        robots = plan['robots']
        for i in rows[:done].tolist():      # a run is a few robots: no numpy for them
            robots[i].avoid_count = int(avoid[i])
        return done

    def _gather(self, plan):
        """This step's state of every robot, as the kernel reads it (a finder's entry: not
        the kernel's case)."""
        work = self.rules['work']
        simple, avoid, carrying = [], [], []
        for r, finder in zip(plan['robots'], plan['finders'], strict=True):
            if finder is not None:
                simple.append(False)
                avoid.append(0)
                carrying.append(0)
                continue
            simple.append(r.mode == work and not r.hungry())
            avoid.append(r.avoid_count)
            carrying.append(r.pos.get_flag_count() > 0)
        plan['state'] = dict(simple=np.array(simple, np.bool_),
                             avoid=np.array(avoid, np.int64),
                             carrying=np.array(carrying, np.int64))


class FasrPositionBatch:
    """fasr's Forager.position_update in turn: in one kernel the robots away from the source
    and the sink, whose update only notes that they are not at the sink (`at_dest`); a
    robot near either runs in Python (it may take or give a flag)."""

    def __init__(self, rules):
        self.rules = rules          # fasr's constants, as a dict (fasr.py gives them)

    def prepare(self, entries):
        """The robots and their poses' rows, or None when they do not share one array."""
        robots = [callback.function.__self__ for callback, _, _ in entries]
        rows = [r.pos.pose_rows() for r in robots]
        if not rows or any(pose is not rows[0][0] for pose, _ in rows):
            return None
        return dict(robots=robots, pose=rows[0][0],
                    row=np.array([row for _, row in rows], np.int64))

    def run(self, plan, rows):
        rules = self.rules
        done = _away_all(rows, plan['pose'], plan['row'], rules['source'][0],
                         rules['source'][1], rules['source_radius'], rules['sink'][0],
                         rules['sink'][1], rules['sink_radius'])
        robots = plan['robots']
        for i in rows[:done].tolist():
            robots[i].at_dest = False
        return done


@kernel
def _away_all(rows, pose, row, source_x, source_y, source_radius, sink_x, sink_y,
              sink_radius):
    """How many of the robots `rows`, in turn, are neither within source_radius of the
    source nor within sink_radius of the sink (position_update's tests; hypot is the C
    library's, as in fasr.py and Stage)."""
    for j in range(rows.shape[0]):
        p = row[rows[j]]
        x = pose[p, 0]
        y = pose[p, 1]
        if math.hypot(source_x - x, source_y - y) < source_radius or \
                math.hypot(sink_x - x, sink_y - y) < sink_radius:
            return j
    return rows.shape[0]


@kernel
def _work_all(rows, simple, avoid, carrying, headings, beams, first, samples, pose, row,
              command, mode, table, pointers, front, stop, avoid_speed, avoid_turn,
              avoid_duration, cruise, cell_origin, cell_size, cells):
    """fasr's laser update of the robots `rows` in turn while each is the simple case;
    returns how many were done (the next is called on its own)."""
    for j in range(rows.shape[0]):
        i = rows[j]
        if not simple[i]:
            return j
        p = row[i]
        if avoid_step_in_kernel(beams[first[i]:first[i] + samples[i]], avoid, i, command,
                                mode, p, table, pointers, front, stop, avoid_speed,
                                avoid_turn, avoid_duration):
            continue
        x = pose[p, 0]
        y = pose[p, 1]
        if not (math.isfinite(x) and math.isfinite(y)):
            return j                                  # Python's int() refuses it
        column = min(max(int((x + cell_origin) / cell_size), 0), cells - 1)
        line = min(max(int((y + cell_origin) / cell_size), 0), cells - 1)
        turn = normalize(headings[carrying[i], line, column] - pose[p, 3])
        if not math.isfinite(turn):                   # set_turn_speed refuses it
            return j
        command[p, 0] = cruise
        command[p, 3] = turn
        mode[p] = VELOCITY
    return rows.shape[0]
