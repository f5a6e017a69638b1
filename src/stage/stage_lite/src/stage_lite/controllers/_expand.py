"""What Stage's two benchmark controllers share (expand_swarm, expand_pioneer): the sum of
a ranger's sensors' first ranges along their headings gives the turn; the robot drives only
while the sensors ahead read enough. Not a controller itself (no init).
"""
import math
from dataclasses import dataclass


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
    ranger.add_callback('update', lambda rgr, _: steer(position, rgr, law, headings))
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
