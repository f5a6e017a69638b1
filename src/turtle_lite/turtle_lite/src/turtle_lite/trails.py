"""What rviz draws of a lesson: the arena outline and each robot's trail, bounded in length.

No rospy: points are (x, y) in metres in the world frame.
"""

import math
from collections import deque

from course_common.arena import WORLD_SIZE_M
from course_common.finite import is_finite_number


def arena_outline(size_m=WORLD_SIZE_M):
    """The closed square (0, 0)-(size, size) as 5 points, the walls turtlesim clamps at."""
    if not is_finite_number(size_m) or size_m <= 0:
        raise ValueError('arena size %r: expected a finite number > 0 (m)' % (size_m,))
    s = float(size_m)
    return [(0.0, 0.0), (s, 0.0), (s, s), (0.0, s), (0.0, 0.0)]


class Trail:
    """The last max_points positions of one robot, at least spacing_m apart.

    Bounded so rviz's line strip and the marker messages stay small however long a lesson runs.
    A robot standing still adds nothing.
    """

    def __init__(self, max_points, spacing_m):
        if not isinstance(max_points, int) or isinstance(max_points, bool) or max_points < 2:
            raise ValueError('trail length %r: expected an integer >= 2 (points)' % (max_points,))
        if not is_finite_number(spacing_m) or spacing_m < 0:
            raise ValueError('trail spacing %r: expected a finite number >= 0 (m)'
                             % (spacing_m,))
        self._points = deque(maxlen=max_points)
        self._spacing_m = float(spacing_m)

    def add(self, x, y):
        """Appends (x, y) if it is spacing_m or more from the last point; True if appended.

        Non-finite positions are refused (ValueError): one would blank rviz's whole strip.
        """
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError('trail point (%r, %r): expected finite numbers' % (x, y))
        if self._points:
            last_x, last_y = self._points[-1]
            if math.hypot(x - last_x, y - last_y) < self._spacing_m:
                return False
        self._points.append((float(x), float(y)))
        return True

    def points(self):
        """The points, oldest first."""
        return list(self._points)

    def __len__(self):
        return len(self._points)


#: Robot colours (r, g, b in 0..1), cycled in the order robots are first seen: distinct on
#: rviz's dark grey background and none of them the arena's yellow.
PALETTE = ((0.20, 0.80, 0.20), (0.95, 0.30, 0.25), (0.30, 0.60, 1.00), (0.90, 0.40, 0.90),
           (0.20, 0.90, 0.90), (1.00, 0.60, 0.20), (0.70, 0.70, 0.70), (0.60, 0.45, 0.25))
ARENA_RGB = (1.0, 0.85, 0.0)


def robot_color(index):
    """The colour of the index-th robot seen (index >= 0), cycling through PALETTE."""
    if not isinstance(index, int) or isinstance(index, bool) or index < 0:
        raise ValueError('robot index %r: expected an integer >= 0' % (index,))
    return PALETTE[index % len(PALETTE)]
