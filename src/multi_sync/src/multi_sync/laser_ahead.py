"""What a robot's laser sees ahead: the nearest reading inside a cone around its heading (no rospy).

A scan is sensor_msgs/LaserScan's numbers: beam i points at angle_min + i * angle_increment
(rad, counter-clockwise positive, 0 = the laser's forward axis, which on Stage's erratic is
the robot's heading), and reads ranges[i] metres from the laser. Readings outside
[range_min, range_max) are not obstacles: NaN, below range_min (invalid), and range_max
itself, which is how Stage reports a beam that hit nothing.
"""
import math

from course_common.finite import is_finite_number

# Beams whose angle is this close to the cone's edge count as inside it (float rounding of
# angle_min + i * angle_increment must not drop the edge beam).
EDGE_TOL_RAD = 1e-9


def _check(name, value):
    if not is_finite_number(value):
        raise ValueError('%s = %r: expected a finite number' % (name, value))


def cone_indices(n_beams, angle_min_rad, angle_increment_rad, half_angle_rad):
    """range(first, last + 1) of the beams whose angle lies within half_angle_rad of 0.

    Raises ValueError for a non-finite angle, a zero increment, or a half angle outside
    (0, pi]. An increment may be negative (a scan taken clockwise).
    """
    _check('angle_min', angle_min_rad)
    _check('angle_increment', angle_increment_rad)
    _check('half_angle', half_angle_rad)
    if angle_increment_rad == 0.0:
        raise ValueError('angle_increment = 0: beams must be spread over an angle')
    if not 0.0 < half_angle_rad <= math.pi:
        raise ValueError('half_angle = %r: expected a cone half angle in (0, pi] rad'
                         % half_angle_rad)
    ends = sorted(((-half_angle_rad - angle_min_rad) / angle_increment_rad,
                   (half_angle_rad - angle_min_rad) / angle_increment_rad))
    tol = EDGE_TOL_RAD / abs(angle_increment_rad)
    first = max(0, math.ceil(ends[0] - tol))
    last = min(n_beams - 1, math.floor(ends[1] + tol))
    return range(first, last + 1)


def nearest_ahead_m(ranges, angle_min_rad, angle_increment_rad, range_min_m, range_max_m,
                    half_angle_rad):
    """The nearest obstacle reading (m from the laser) inside the cone, or inf if none.

    The cone is every beam within half_angle_rad of the laser's forward axis. Raises
    ValueError for bad scan geometry (see cone_indices) or range limits that are not
    0 <= range_min < range_max (finite).
    """
    _check('range_min', range_min_m)
    _check('range_max', range_max_m)
    if not 0.0 <= range_min_m < range_max_m:
        raise ValueError('range_min = %r, range_max = %r: expected 0 <= range_min < range_max'
                         % (range_min_m, range_max_m))
    nearest = math.inf
    for i in cone_indices(len(ranges), angle_min_rad, angle_increment_rad, half_angle_rad):
        r = ranges[i]
        # NaN fails both comparisons, so it is skipped too.
        if range_min_m <= r < range_max_m and r < nearest:
            nearest = r
    return nearest
