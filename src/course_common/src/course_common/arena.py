"""turtlesim's arena, the square world every lesson drives in: its size and its centre.

Pure, and without numpy (tools and lesson models import it without the simulator's maths).
Frame: metres, origin at the bottom-left corner, x right, y up (turtlesim's world frame).
turtlesim draws its world on a 500 x 500 px canvas at 45 px per metre and puts the far wall
at (500 - 1) / 45 m; turtle1 spawns in the middle, at a coordinate rounded to float32 because
turtlesim's spawn takes floats.
"""
import struct

from course_common.finite import is_finite_number

#: Pixels per metre: the height of turtlesim's first turtle sprite.
METER_PX = 45.0
#: turtlesim's canvas (window) side, in pixels.
CANVAS_PX = 500
#: The world's side in metres: (500 - 1) / 45 = 11.088889, as turtlesim computes it.
WORLD_SIZE_M = (CANVAS_PX - 1) / METER_PX
#: The world's exact centre on both axes, in metres (5.5444444...).
CENTRE_M = WORLD_SIZE_M / 2.0
#: turtle1's spawn coordinate on both axes: CENTRE_M rounded to float32, 5.5444446 m.
SPAWN_M = struct.unpack('f', struct.pack('f', CENTRE_M))[0]


def inside(x, y, size_m=WORLD_SIZE_M):
    """True if (x, y) m lies in the closed square [0, size_m] x [0, size_m] (walls included).

    ValueError if x, y or size_m is not a finite number, or size_m <= 0.
    """
    for name, value in (('x', x), ('y', y), ('size_m', size_m)):
        if not is_finite_number(value):
            raise ValueError('%s = %r: expected a finite number (m)' % (name, value))
    if size_m <= 0.0:
        raise ValueError('size_m = %r: expected a finite number > 0 (m)' % (size_m,))
    return 0.0 <= x <= size_m and 0.0 <= y <= size_m


def arena_outline(size_m=WORLD_SIZE_M):
    """The closed square (0, 0)-(size, size) as 5 points, the walls turtlesim clamps at."""
    if not is_finite_number(size_m) or size_m <= 0:
        raise ValueError('arena size %r: expected a finite number > 0 (m)' % (size_m,))
    s = float(size_m)
    return [(0.0, 0.0), (s, 0.0), (s, s), (0.0, s), (0.0, 0.0)]
