"""The convoy's gaps as rviz shows them: who follows whom, how far, where the label goes (pure).

Positions are (x, y) in metres in the world frame.
"""

import math
from collections import namedtuple

from course_common.finite import is_finite_number

GapLabel = namedtuple('GapLabel', 'follower leader gap_m mid_x mid_y text')
"""One follower's distance to its leader, the midpoint between them, and the label's text."""


def chain_links(robots):
    """[(follower, leader)] of a convoy given leader first: [r1, r2, r3] -> [(r2, r1), (r3, r2)].

    Raises ValueError for fewer than two robots, empty names or a robot listed twice.
    """
    robots = list(robots) if isinstance(robots, (list, tuple)) else None
    if robots is None or len(robots) < 2:
        raise ValueError('a convoy needs 2 or more robots, leader first, e.g. '
                         '[robot1, robot2, robot3]')
    if not all(isinstance(r, str) and r.strip() for r in robots):
        raise ValueError('robot names must be non-empty strings: %r' % (robots,))
    if len(set(robots)) != len(robots):
        raise ValueError('a robot is listed twice: %r' % (robots,))
    return list(zip(robots[1:], robots[:-1], strict=True))


def gap_label(follower, leader, follower_xy, leader_xy):
    """The GapLabel of follower behind leader. Raises ValueError on non-finite positions."""
    values = tuple(follower_xy) + tuple(leader_xy)
    if len(values) != 4 or not all(is_finite_number(v) for v in values):
        raise ValueError('positions of %s and %s must be finite (x, y): %r, %r'
                         % (follower, leader, follower_xy, leader_xy))
    fx, fy, lx, ly = (float(v) for v in values)
    gap = math.hypot(lx - fx, ly - fy)
    return GapLabel(follower, leader, gap, 0.5 * (fx + lx), 0.5 * (fy + ly),
                    '%s -> %s %.2f m' % (follower, leader, gap))
