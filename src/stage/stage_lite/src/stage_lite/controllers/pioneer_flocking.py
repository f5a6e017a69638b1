"""Stage's `pioneer_flocking` (examples/ctrl/pioneer_flocking.cc), for pioneer_flocking.world
and SFU.world: steer along the sum of the first 8 sonar ranges (gain 0.3), drive at 0.4 m/s
while the front sonars read enough, and then turn also toward the heading of the nearest
robot the fiducial finder saw at its last update (gain 0.3); blocked and turning slowly,
turn by a drand48() draw instead (Stage seeds drand48 from the clock: its flocks differ
from run to run; here the world's seed fixes them). Before the finder's first update Stage
reads an uninitialised pointer; here that counts as no robot seen.

The robots' callbacks that come one after the other run in one kernel (BATCH, scheduler.py's
batches), in the same order: each reads its own sonars, finder and flocking state and
writes its own robot's command, and the drand48() draws come in turn from the world's
stream.
"""
import math
import weakref

import numpy as np

from stage_lite.model.glibc_random import drand48_next
from stage_lite.model.jit import kernel
from stage_lite.model.stage_api_sensors import FiducialApi

from ._expand import all_clear, sensors_sum, set_velocity

SPEED = 0.4               # m/s
EXPAND_GAIN = 0.3         # turn per rad of the sonars' resultant
FLOCK_GAIN = 0.3          # turn per rad of the nearest robot's relative heading
SAFE_DISTANCE = 1.0       # m
SAFE_ANGLE = 0.5          # rad
SONARS = 8                # the first sonars summed
#: (sonar, the least range it must read to drive)
CLEAR_AHEAD = ((3, SAFE_DISTANCE), (4, SAFE_DISTANCE), (5, SAFE_DISTANCE),
               (6, SAFE_DISTANCE / 2.0), (2, SAFE_DISTANCE), (1, SAFE_DISTANCE / 2.0))
SLOW_TURN = 0.1           # rad/s: below it a blocked robot turns by drand48() instead
CLEAR_K = np.array([k for k, _ in CLEAR_AHEAD], np.int64)
CLEAR_LEAST = np.array([least for _, least in CLEAR_AHEAD], np.float64)
RANGER, FINDER = 0, 1     # the batch's two kinds of callback


def init(model, args):
    if model.type != 'position':
        raise TypeError('pioneer_flocking drives a position model, not a %s' % model.type)
    ranger = model.get_unused_model_of_type('ranger')
    if ranger is None:
        raise LookupError('%s carries no unused ranger (its sonars)' % model.token)
    if len(ranger.sensors) < SONARS:
        raise ValueError('%s has %d sensors; pioneer_flocking reads %d'
                         % (ranger.token, len(ranger.sensors), SONARS))
    flocker = Flocker(model, ranger)
    ranger.add_callback('update', flocker.ranger_update)
    finder = model.get_unused_model_of_type('fiducial')
    if finder is None:
        raise LookupError('%s carries no unused fiducial finder' % model.token)
    finder.add_callback('update', flocker.fiducial_update)
    finder.read_nearest_only()
    finder.subscribe()
    ranger.subscribe()
    model.subscribe()


class Flock:
    """The flocking state of a world's flockers, one row each (whether it saw a robot at its
    finder's last update, and that robot's relative heading), for the batch's kernel."""

    def __init__(self):
        self.sees = np.zeros(0, np.bool_)
        self.heading = np.zeros(0, np.float64)

    def add(self):
        """A new row (False, 0.0); its number."""
        self.sees = np.append(self.sees, False)
        self.heading = np.append(self.heading, 0.0)
        return len(self.sees) - 1


_flocks = weakref.WeakKeyDictionary()     # a world (its controllers' handle) -> its Flock


class Flocker:
    """One robot's flocking state: the nearest robot last seen, and its relative heading
    (its row of the world's Flock)."""

    def __init__(self, position, ranger):
        self.position = position
        self.ranger = ranger
        self.headings = [s.pose.a for s in ranger.sensors[:SONARS]]
        self.flock = _flocks.setdefault(position.world, Flock())
        self.row = self.flock.add()

    @property
    def sees_one(self):
        return bool(self.flock.sees[self.row])

    @sees_one.setter
    def sees_one(self, value):
        self.flock.sees[self.row] = value

    @property
    def heading_error(self):
        return float(self.flock.heading[self.row])

    @heading_error.setter
    def heading_error(self, value):
        self.flock.heading[self.row] = value

    def ranger_update(self, ranger, _):
        sensors = ranger.sensors
        first = [s.ranges[0] for s in sensors]
        dx = dy = 0.0
        for r, a in zip(first[:SONARS], self.headings, strict=True):
            dx += r * math.cos(a)
            dy += r * math.sin(a)
        if dx == 0 or dy == 0:
            return False
        resultant = math.atan2(dy, dx)
        forward = 0.0
        turn = EXPAND_GAIN * resultant
        if all(first[k] > least for k, least in CLEAR_AHEAD) and abs(resultant) < SAFE_ANGLE:
            forward = SPEED
            if self.sees_one:
                turn += FLOCK_GAIN * self.heading_error
        elif abs(turn) < SLOW_TURN:
            turn = self.position.world.drand48()
        self.position.set_speed(forward, 0.0, turn)
        return False

    def fiducial_update(self, finder, _):
        nearest = finder.nearest()         # the first of the least range it saw
        self.sees_one = nearest is not None
        if nearest is not None:          # otherwise the last heading seen stays
            self.heading_error = nearest[1]
        return False


class _Batch:
    """Flockers' callbacks in turn, in one kernel (scheduler.py's batch protocol)."""

    @staticmethod
    def prepare(entries):
        """The callbacks' tables, or None when a sensor or a robot is not the world's."""
        flockers = []
        place = {}
        kind = np.zeros(len(entries), np.int64)
        who = np.zeros(len(entries), np.int64)
        finders = []
        for e, (callback, _, _) in enumerate(entries):
            flocker = callback.function.__self__
            if flocker not in place:
                place[flocker] = len(flockers)
                flockers.append(flocker)
            who[e] = flocker.row
            kind[e] = RANGER if callback.function.__func__ is Flocker.ranger_update else FINDER
            finders.append(callback.handle if kind[e] == FINDER else None)
        if any(f.flock is not flockers[0].flock for f in flockers):
            return None
        n = len(flockers[0].flock.sees)
        first = np.zeros((n, SONARS), np.int64)
        headings = np.zeros((n, SONARS))
        row = np.zeros(n, np.int64)
        arrays = None
        for flocker in flockers:
            f = flocker.row
            places = [s.first_range_at() for s in flocker.ranger.sensors[:SONARS]]
            goal, mode, row[f] = flocker.position.command_rows()
            if None in places:
                return None
            here = (places[0][0], goal, mode)
            arrays = arrays or here
            if any(p[0] is not arrays[0] for p in places) or here[1] is not arrays[1] \
                    or here[2] is not arrays[2]:
                return None
            first[f] = [at for _, at in places]
            headings[f] = flocker.headings
        beams, goal, mode = arrays
        return dict(flock=flockers[0].flock, finders=finders, kind=kind, who=who, first=first,
                    headings=headings, row=row, beams=beams, goal=goal, mode=mode,
                    rand48=flockers[0].position.world.drand48_state())

    @staticmethod
    def run(plan, rows):
        flock = plan['flock']
        found = np.zeros(len(plan['kind']), np.bool_)
        near = np.zeros(len(plan['kind']), np.float64)
        finders = plan['finders']
        at = rows[plan['kind'][rows] == FINDER]
        # their nearest, unmade, all from one update_all's array at once; else one by one
        near_of = (FiducialApi.nearest_rows(list(map(finders.__getitem__, at.tolist())))
                   if at.size else None)
        if near_of is not None:
            found[at] = near_of[:, 2] != 0.0
            near[at] = near_of[:, 1]
        else:
            for e in at.tolist():
                nearest = finders[e].nearest()
                if nearest is not None:
                    found[e] = True
                    near[e] = nearest[1]
        done = _flock_all(rows, plan['kind'], plan['who'], found, near, plan['beams'],
                          plan['first'], plan['headings'], plan['row'], flock.sees,
                          flock.heading, plan['goal'], plan['mode'], plan['rand48'])
        return done


BATCH = _Batch()
Flocker.ranger_update.batch = BATCH
Flocker.fiducial_update.batch = BATCH


@kernel
def _flock_all(rows, kind, who, found, near, beams, first, headings, row, sees, heading, goal,
               mode, rand48):
    """Flocker.ranger_update and .fiducial_update of the entries `rows` in turn; returns how
    many were done (a command that would not be finite is left to be called on its own)."""
    n = rows.shape[0]
    for j in range(n):
        e = rows[j]
        f = who[e]
        if kind[e] == FINDER:
            sees[f] = found[e]
            if found[e]:
                heading[f] = near[e]
            continue
        dx, dy = sensors_sum(beams, first[f], headings[f], SONARS)
        if dx == 0 or dy == 0:
            continue
        resultant = math.atan2(dy, dx)
        forward = 0.0
        turn = EXPAND_GAIN * resultant
        if (all_clear(beams, first[f], CLEAR_K, CLEAR_LEAST, CLEAR_K.shape[0])
                and abs(resultant) < SAFE_ANGLE):
            forward = SPEED
            if sees[f]:
                turn += FLOCK_GAIN * heading[f]
        elif abs(turn) < SLOW_TURN:
            turn = drand48_next(rand48)
        if not (math.isfinite(forward) and math.isfinite(turn)):
            return j
        set_velocity(goal, mode, row[f], forward, turn)
    return n
