"""A robot's trail, bounded in length: what rviz's markers (turtle_lite's lesson_markers) and
stageros's pictures draw of where each robot went.

No rospy: points are (x, y) in metres in the world frame.
"""

import math
from collections import deque

from course_common.finite import is_finite_number


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
        if not (is_finite_number(x) and is_finite_number(y)):
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

    def clear(self):
        self._points.clear()

    def __len__(self):
        return len(self._points)
