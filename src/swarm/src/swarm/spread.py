"""How spread out a swarm is (pure): the robots' mean distance from their centroid, m."""
import math


def spread_m(points):
    """Mean distance of the (x, y) points from their centroid, m; ValueError if empty."""
    points = list(points)
    if not points:
        raise ValueError('no robots to measure')
    cx = sum(x for x, _ in points) / len(points)
    cy = sum(y for _, y in points) / len(points)
    return sum(math.hypot(x - cx, y - cy) for x, y in points) / len(points)
