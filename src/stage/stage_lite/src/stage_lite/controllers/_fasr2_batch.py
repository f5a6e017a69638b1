"""fasr2's position updates, robot after robot, in one kernel (scheduler.py's batch protocol).

Most of fasr2's updates are one case: a working robot away from its goal, not waiting, not
hungry, with a plan that advises; it either avoids (a new avoid drawing its count from
random()'s stream, glibc_random.random_next) or turns to the plan's heading and cruises. The
kernel does exactly that case, rule for rule as fasr2.py (the same comparisons, the C
library's hypot, atan2 and Stage's normalize), and stops at the first robot in any other
case (at its goal, waiting, hungry, docking or undocking, no plan or advice, its goal
moved): that robot's update runs in Python, and the kernel goes on after it.

What the kernel reads of each robot's Python state (mode, avoid count, task, goal, plan,
pack) is gathered once a step: during the update callbacks a robot's update changes only its
own state (the packs charge and drain after them), and each robot updates once a step.
"""
import math

import numpy as np

from stage_lite.model.jit import kernel
from stage_lite.model.motion import normalize

from ._avoid import VELOCITY, avoid_step_in_kernel, laser_rows
from ._fasr2_plans import best_node, reach

OTHER_GOAL, SOURCE_GOAL, SINK_GOAL = 0, 1, 2
# a robot the kernel leaves to its own update (the other fields unread)
NOT_SIMPLE = (False, OTHER_GOAL, 0, 0, 0, False, -1, 0.0, 0.0, False)


class Fasr2Batch:
    """fasr2's Robot.update in turn, in one kernel where the case allows (see the module)."""

    def __init__(self, rules):
        self.rules = rules          # fasr2's constants, as a dict (fasr2.py gives them)

    def prepare(self, entries):
        """The robots' fixed tables, or None when they do not share the world's arrays."""
        robots = [callback.function.__self__ for callback, _, _ in entries]
        n = len(robots)
        plan = dict(robots=robots, step=None, first=np.zeros(n, np.int64),
                    samples=np.zeros(n, np.int64), row=np.zeros(n, np.int64))
        arrays = None
        for i, r in enumerate(robots):
            found = laser_rows(r.pos, r.scan, arrays)
            if found is None:
                return None
            arrays, plan['first'][i], plan['row'][i] = found
            plan['samples'][i] = len(r.scan.ranges)
        plan['beams'], plan['goal'], plan['mode'], plan['pose'] = arrays
        shared = robots[0].shared
        if any(r.shared is not shared for r in robots):
            return None
        plan['shared'] = shared
        # the goals a robot can have: each task's source and sink, the fuel zone
        goals = [m for t in shared.tasks for m in (t.source, t.sink)] + [robots[0].fuel_zone]
        plan['goals'] = goals
        plan['goal_slot'] = {id(m): k for k, m in enumerate(goals)}
        plan['random'] = robots[0].pos.world.random_stream()
        return plan

    def run(self, plan, rows):
        robots = plan['robots']
        now = robots[0].pos.world.sim_time_now()
        if plan['step'] != now:
            self._gather(plan)
            plan['step'] = now
        state = plan['state']
        rules = self.rules
        xs, ys, off = plan['shared'].plan_nodes()
        stream = plan['random']
        done = _work_all(rows, state['simple'], state['kind'], state['goal'], state['wait'],
                         state['avoid'], state['hungry'], state['plan'], state['cached'],
                         plan['goal_xy'], plan['goal_half'], xs, ys, off, plan['beams'],
                         plan['first'], plan['samples'], plan['pose'], plan['row'],
                         plan['goal'], plan['mode'], stream.table, stream.pointers,
                         rules['front'], rules['stop'], rules['avoid_speed'],
                         rules['avoid_turn'], rules['avoid_duration'], rules['cruise'],
                         rules['replan_move'], rules['advice_range'], rules['lane_bias'])
        did = rows[:done]
        avoid = state['avoid']
        for i in did[avoid[did] != state['avoid_before'][did]].tolist():
            robots[i].avoid_count = int(avoid[i])
        for i in did[state['ahoy'][did]].tolist():
            robots[i].charger_ahoy = False          # each update's first act
        return done

    def _gather(self, plan):
        """This step's state of every robot, as the kernel reads it."""
        work = self.rules['work']
        slot = plan['goal_slot']
        tasks = plan['shared'].tasks
        rows = []
        for r in plan['robots']:
            k = slot.get(id(r.goal))
            if r.mode != work or r.subscribed['fiducial'] or k is None:
                rows.append(NOT_SIMPLE)
                continue
            task = tasks[r.task]
            kind = SOURCE_GOAL if r.goal is task.source else \
                SINK_GOAL if r.goal is task.sink else OTHER_GOAL
            cached = r.cached_goal_pose
            rows.append((True, kind, k, r.wait_started_at, r.avoid_count, r.hungry(),
                         -1 if r.plan is None else r.plan.id, cached.x, cached.y,
                         r.charger_ahoy))
        (simple, kind, goal, wait, avoid, hungry, plan_id, cached_x, cached_y,
         ahoy) = zip(*rows, strict=True)
        plan['state'] = dict(
            simple=np.array(simple, np.bool_), kind=np.array(kind, np.int64),
            goal=np.array(goal, np.int64), wait=np.array(wait, np.int64),
            avoid=np.array(avoid, np.int64), avoid_before=np.array(avoid, np.int64),
            hungry=np.array(hungry, np.bool_), plan=np.array(plan_id, np.int64),
            cached=np.column_stack((cached_x, cached_y)).astype(np.float64),
            ahoy=np.array(ahoy, np.bool_))
        goals = plan['goals']
        poses = [m.get_pose() for m in goals]
        plan['goal_xy'] = np.array([(p.x, p.y) for p in poses], np.float64)
        plan['goal_half'] = np.array([reach(m) for m in goals], np.float64)


@kernel
def _work_all(rows, simple, kind, goal, wait, avoid, hungry, plan, cached, goal_xy, goal_half,
              xs, ys, off, beams, first, samples, pose, row, command, mode, table, pointers,
              front, stop, avoid_speed, avoid_turn, avoid_duration, cruise, replan_move,
              advice_range, lane_bias):
    """fasr2's update of the robots `rows` in turn while each is the simple case; returns
    how many were done (the next is called on its own)."""
    for j in range(rows.shape[0]):
        i = rows[j]
        if not simple[i]:
            return j
        p = row[i]
        x = pose[p, 0]
        y = pose[p, 1]
        a = pose[p, 3]
        g = goal[i]
        if kind[i] != OTHER_GOAL:                    # at_source / at_sink
            if math.hypot(goal_xy[g, 0] - x, goal_xy[g, 1] - y) < goal_half[g]:
                return j
            if kind[i] == SOURCE_GOAL and wait[i] > 0:     # waiting: a draw
                return j
        if avoid_step_in_kernel(beams[first[i]:first[i] + samples[i]], avoid, i, command,
                                mode, p, table, pointers, front, stop, avoid_speed,
                                avoid_turn, avoid_duration):
            continue
        if hungry[i] or plan[i] < 0:
            return j
        k = plan[i]
        best = best_node(xs, ys, off[k], off[k + 1], x, y, advice_range)
        if best < 0:
            return j
        if math.hypot(goal_xy[g, 0] - cached[i, 0], goal_xy[g, 1] - cached[i, 1]) > replan_move:
            return j
        advice = normalize(math.atan2(ys[best] - y, xs[best] - x) + lane_bias)
        turn = normalize(advice - a)
        if not math.isfinite(turn):                   # set_turn_speed refuses it
            return j
        command[p, 3] = turn
        mode[p] = VELOCITY
        command[p, 0] = cruise
    return rows.shape[0]

