"""Stage's benchmark controller `expand_swarm` (worlds/benchmark/expand_swarm.cc), for the
swarmbots of hospital.world: steer along the sum of the 12 infrared ranges (each sensor's
first range along its heading), at 0.3 m/s while the front arc is clear.
"""
from . import _expand as expand

SPEED = 0.3               # m/s
TURN_GAIN = 1.0
SAFE_DISTANCE = 0.5       # m
SAFE_ANGLE = 0.5          # rad
#: (sensor, the least range it must read to drive): the front and the arcs beside it
CLEAR_AHEAD = ((0, SAFE_DISTANCE), (1, SAFE_DISTANCE / 1.5), (2, SAFE_DISTANCE / 3.0),
               (3, SAFE_DISTANCE / 5.0), (9, SAFE_DISTANCE / 5.0), (10, SAFE_DISTANCE / 3.0),
               (11, SAFE_DISTANCE / 1.5))


def init(model, args):
    expand.start(model, expand.Law(SPEED, TURN_GAIN, SAFE_ANGLE, CLEAR_AHEAD),
                 subscribe_position_first=True)
