"""Stage's `pioneer_flocking` (examples/ctrl/pioneer_flocking.cc), for pioneer_flocking.world
and SFU.world: steer along the sum of the first 8 sonar ranges (gain 0.3), drive at 0.4 m/s
while the front sonars read enough, and then turn also toward the heading of the nearest
robot the fiducial finder saw at its last update (gain 0.3); blocked and turning slowly,
turn by a drand48() draw instead (Stage seeds drand48 from the clock: its flocks differ
from run to run; here the world's seed fixes them). Before the finder's first update Stage
reads an uninitialised pointer; here that counts as no robot seen.
"""
import math

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
    finder.subscribe()
    ranger.subscribe()
    model.subscribe()


class Flocker:
    """One robot's flocking state: the nearest robot last seen, and its relative heading."""

    def __init__(self, position, ranger):
        self.position = position
        self.headings = [s.pose.a for s in ranger.sensors[:SONARS]]
        self.sees_one = False
        self.heading_error = 0.0

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
        nearest = None
        for seen in finder.fiducials:
            if seen.range < (nearest.range if nearest is not None else 1e6):
                nearest = seen
        self.sees_one = nearest is not None
        if nearest is not None:          # otherwise the last heading seen stays
            self.heading_error = nearest.geom[3]
        return False
