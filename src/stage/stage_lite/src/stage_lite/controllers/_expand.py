"""What Stage's two benchmark controllers share (expand_swarm, expand_pioneer): the sum of
a ranger's sensors' first ranges along their headings gives the turn; the robot drives only
while the sensors ahead read enough. Not a controller itself (no init).

Each robot's RangerUpdate is a Steering; the robots whose rangers updated one after the
other steer in one kernel (BATCH, scheduler.py's batches): the law reads only its own
ranger's readings and writes only its own robot's command, with no random draw, so doing
them in turn in a kernel is doing them in turn.
"""
import math
from dataclasses import dataclass

import numpy as np

from stage_lite.model.jit import kernel, njit
from stage_lite.model.robot_state import MODE_CODE

VELOCITY = MODE_CODE['velocity']


@dataclass(frozen=True)
class Law:
    speed: float            # m/s when clear ahead
    turn_gain: float
    safe_angle: float       # rad: drive only when the resultant is within it
    clear_ahead: tuple      # ((sensor index, least range), ...), checked in order


def start(position, law, subscribe_position_first, takes_laser=False):
    """Init: the position's first unused ranger steers it (its update callback); both
    subscribed, in the controller's order."""
    if position.type != 'position':
        raise TypeError('drives a position model, not a %s' % position.type)
    ranger = position.get_unused_model_of_type('ranger')
    if ranger is None:
        raise LookupError('%s carries no unused ranger' % position.token)
    needed = 1 + max(k for k, _ in law.clear_ahead)
    if len(ranger.sensors) < needed:
        raise ValueError('%s has %d sensors; this controller reads %d'
                         % (ranger.token, len(ranger.sensors), needed))
    headings = [s.pose.a for s in ranger.sensors]
    ranger.add_callback('update', Steering(position, law, headings))
    if takes_laser and position.get_unused_model_of_type('ranger') is None:
        raise LookupError('%s carries no second ranger (the laser)' % position.token)
    if subscribe_position_first:
        position.subscribe()
        ranger.subscribe()
    else:
        ranger.subscribe()
        position.subscribe()


def steer(position, ranger, law, headings):
    """The controller's RangerUpdate."""
    sensors = ranger.sensors
    first = [s.ranges[0] for s in sensors]
    dx = dy = 0.0
    for r, a in zip(first, headings, strict=True):
        dx += r * math.cos(a)
        dy += r * math.sin(a)
    if dx == 0 or dy == 0:
        return False
    resultant = math.atan2(dy, dx)
    forward = 0.0
    if all(first[k] > least for k, least in law.clear_ahead) \
            and abs(resultant) < law.safe_angle:
        forward = law.speed
    position.set_speed(forward, 0.0, law.turn_gain * resultant)
    return False


class Steering:
    """One robot's RangerUpdate callback: steer() of its position by its law."""

    def __init__(self, position, law, headings):
        self.position = position
        self.law = law
        self.headings = headings

    def __call__(self, ranger, _):
        return steer(self.position, ranger, self.law, self.headings)


class _Batch:
    """Steerings in turn, in one kernel (scheduler.py's batch protocol)."""

    @staticmethod
    def prepare(entries):
        """The steerings' tables, or None when a sensor or a robot is not the world's
        (then each is called on its own)."""
        steerings = [callback.function for callback, _, _ in entries]
        rangers = [callback.handle for callback, _, _ in entries]
        width = max(len(s.headings) for s in steerings)
        clear = max(len(s.law.clear_ahead) for s in steerings)
        n = len(steerings)
        plan = dict(first=np.zeros((n, width), np.int64), headings=np.zeros((n, width)),
                    count=np.zeros(n, np.int64), clear_k=np.zeros((n, clear), np.int64),
                    clear_least=np.zeros((n, clear)), clear_n=np.zeros(n, np.int64),
                    speed=np.zeros(n), gain=np.zeros(n), safe=np.zeros(n),
                    row=np.zeros(n, np.int64))
        arrays = None
        for i, (s, ranger) in enumerate(zip(steerings, rangers, strict=True)):
            places = [sensor.first_range_at() for sensor in ranger.sensors]
            goal, mode, row = s.position.command_rows()
            if None in places or len(places) != len(s.headings):
                return None
            here = (places[0][0], goal, mode)
            if arrays is None:
                arrays = here
            if any(p[0] is not arrays[0] for p in places) or here[1] is not arrays[1] \
                    or here[2] is not arrays[2]:
                return None
            plan['first'][i, :len(places)] = [at for _, at in places]
            plan['headings'][i, :len(places)] = s.headings
            plan['count'][i] = len(places)
            plan['clear_k'][i, :len(s.law.clear_ahead)] = [k for k, _ in s.law.clear_ahead]
            plan['clear_least'][i, :len(s.law.clear_ahead)] = [v for _, v in s.law.clear_ahead]
            plan['clear_n'][i] = len(s.law.clear_ahead)
            plan['speed'][i] = s.law.speed
            plan['gain'][i] = s.law.turn_gain
            plan['safe'][i] = s.law.safe_angle
            plan['row'][i] = row
        plan['beams'], plan['goal'], plan['mode'] = arrays
        # The headings' cosines and sines once, from the kernel's own math.cos and math.sin:
        # the same values sensors_sum works out at every call.
        plan['cos'], plan['sin'] = heading_trig(plan['headings'])
        return plan

    @staticmethod
    def run(plan, rows):
        return _steer_all(rows, plan['beams'], plan['first'], plan['cos'], plan['sin'],
                          plan['count'], plan['clear_k'], plan['clear_least'], plan['clear_n'],
                          plan['speed'], plan['gain'], plan['safe'], plan['row'], plan['goal'],
                          plan['mode'])


BATCH = _Batch()
Steering.batch = BATCH


@njit(cache=True)
def heading_trig(headings):
    """(cos, sin) of each heading, as sensors_sum's math.cos and math.sin give them."""
    cos = np.empty_like(headings)
    sin = np.empty_like(headings)
    for i in range(headings.shape[0]):
        for k in range(headings.shape[1]):
            cos[i, k] = math.cos(headings[i, k])
            sin[i, k] = math.sin(headings[i, k])
    return cos, sin


@kernel
def _steer_all(rows, beams, first, cos, sin, count, clear_k, clear_least, clear_n, speed,
               gain, safe, row, goal, mode):
    """steer() of the steerings `rows` in turn; returns how many were done (one whose
    command would not be finite is left, with those after it, to be called on its own:
    set_speed raises)."""
    n = rows.shape[0]
    for j in range(n):
        i = rows[j]
        dx, dy = sensors_sum_trig(beams, first[i], cos[i], sin[i], count[i])
        if dx == 0 or dy == 0:
            continue
        resultant = math.atan2(dy, dx)
        forward = 0.0
        if (all_clear(beams, first[i], clear_k[i], clear_least[i], clear_n[i])
                and abs(resultant) < safe[i]):
            forward = speed[i]
        turn = gain[i] * resultant
        if not (math.isfinite(forward) and math.isfinite(turn)):
            return j
        set_velocity(goal, mode, row[i], forward, turn)
    return n


@kernel
def sensors_sum_trig(beams, first, cos, sin, count):
    """sensors_sum with the headings' cosines and sines given (heading_trig)."""
    dx = 0.0
    dy = 0.0
    for k in range(count):
        r = beams[first[k]]
        dx += r * cos[k]
        dy += r * sin[k]
    return dx, dy


@kernel
def sensors_sum(beams, first, headings, count):
    """(dx, dy): the first `count` sensors' first ranges along their headings, added in
    order as the C loops add them (first: each sensor's first beam in beams)."""
    dx = 0.0
    dy = 0.0
    for k in range(count):
        r = beams[first[k]]
        a = headings[k]
        dx += r * math.cos(a)
        dy += r * math.sin(a)
    return dx, dy


@kernel
def all_clear(beams, first, sensors, least, count):
    """Whether each of the first `count` (sensor, least range) pairs reads more than its
    least, in order (C's && stops at the first that does not)."""
    for c in range(count):  # noqa: SIM110 - numba compiles no generator for all()
        if not beams[first[sensors[c]]] > least[c]:
            return False
    return True


@kernel
def set_velocity(goal, mode, r, forward, turn):
    """SetSpeed(forward, 0, turn) of robot row r, in the robots' arrays."""
    goal[r, 0] = forward
    goal[r, 1] = 0.0
    goal[r, 2] = 0.0
    goal[r, 3] = turn
    mode[r] = VELOCITY
