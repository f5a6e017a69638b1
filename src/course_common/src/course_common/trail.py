"""Robots' trails, bounded in length: what rviz's markers (turtle_lite's lesson_markers) and
stageros's pictures draw of where each robot went.

No rospy: points are (x, y) in metres in the world frame.
"""

import numpy as np

from course_common.finite import is_finite_number


class Trails:
    """The last max_points positions of each of `count` robots, each point at least
    spacing_m from the one before it, kept in arrays: a step of a swarm adds every robot's
    point at once (add_all).

    Bounded so rviz's line strip, the marker messages and a picture stay small however long
    a lesson runs. A robot standing still adds nothing; neither does a non-finite position.
    """

    def __init__(self, count, max_points, spacing_m):
        if not isinstance(max_points, int) or isinstance(max_points, bool) or max_points < 2:
            raise ValueError('trail length %r: expected an integer >= 2 (points)' % (max_points,))
        if not is_finite_number(spacing_m) or spacing_m < 0:
            raise ValueError('trail spacing %r: expected a finite number >= 0 (m)'
                             % (spacing_m,))
        self._spacing_m = float(spacing_m)
        self._points = np.zeros((count, max_points, 2))   # rings: pages untouched stay free
        self._next = np.zeros(count, np.int64)             # each ring's next slot
        self._held = np.zeros(count, np.int64)
        self._last = np.full((count, 2), np.nan)           # nan: no point yet

    def add_all(self, xy, indices=None):
        """(n, 2) positions of robots `indices` (default: every robot, in order). Returns
        the bool mask of those appended: finite, and spacing_m or more from the last."""
        xy = np.asarray(xy, np.float64).reshape(-1, 2)
        rows = np.arange(len(self._next)) if indices is None else np.asarray(indices, np.int64)
        gap = np.hypot(xy[:, 0] - self._last[rows, 0], xy[:, 1] - self._last[rows, 1])
        appended = np.isfinite(xy).all(axis=1) & ~(gap < self._spacing_m)  # nan gap: first
        rows, xy = rows[appended], xy[appended]
        if rows.size:
            slots = self._next[rows]
            self._points[rows, slots] = xy
            self._last[rows] = xy
            self._next[rows] = (slots + 1) % self._points.shape[1]
            self._held[rows] = np.minimum(self._held[rows] + 1, self._points.shape[1])
        return appended

    def get(self, index):
        """K x 2 array of robot index's trail, oldest first (K may be 0)."""
        held, end = self._held[index], self._next[index]
        ring = self._points[index]
        if held < ring.shape[0]:
            return ring[:held].copy()
        return np.concatenate([ring[end:], ring[:end]])

    def held(self, index):
        return int(self._held[index])

    def clear(self):
        self._next[:] = 0
        self._held[:] = 0
        self._last[:] = np.nan


class Trail:
    """One robot's trail (Trails' rule): the last max_points positions, at least spacing_m
    apart."""

    def __init__(self, max_points, spacing_m):
        self._trails = Trails(1, max_points, spacing_m)

    def add(self, x, y):
        """Appends (x, y) if it is spacing_m or more from the last point; True if appended.

        Non-finite positions are refused (ValueError): one would blank rviz's whole strip.
        """
        if not (is_finite_number(x) and is_finite_number(y)):
            raise ValueError('trail point (%r, %r): expected finite numbers' % (x, y))
        return bool(self._trails.add_all((x, y))[0])

    def points(self):
        """The points, oldest first."""
        return [tuple(p) for p in self._trails.get(0).tolist()]

    def clear(self):
        self._trails.clear()

    def __len__(self):
        return self._trails.held(0)
