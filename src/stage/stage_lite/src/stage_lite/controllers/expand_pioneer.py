"""Stage's benchmark controller `expand_pioneer` (worlds/benchmark/expand_pioneer.cc), for
the pioneers of cave.world: steer along the sum of the sonar ranges, at 0.2 m/s while the
front sonars are clear. Its second ranger (the laser) is taken but not read.
"""
from . import _expand as expand

SPEED = 0.2               # m/s
TURN_GAIN = 1.0
SAFE_DISTANCE = 0.75      # m
SAFE_ANGLE = 0.5          # rad
CLEAR_AHEAD = ((3, SAFE_DISTANCE), (4, SAFE_DISTANCE), (5, SAFE_DISTANCE / 2.0),
               (6, SAFE_DISTANCE / 4.0), (2, SAFE_DISTANCE / 2.0), (1, SAFE_DISTANCE / 4.0))


def init(model, args):
    expand.start(model, expand.Law(SPEED, TURN_GAIN, SAFE_ANGLE, CLEAR_AHEAD),
                 subscribe_position_first=False, takes_laser=True)
