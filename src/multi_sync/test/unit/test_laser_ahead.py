"""Unit tests for multi_sync.laser_ahead: the nearest reading in the cone ahead of a scan."""
import math

import pytest
from multi_sync.laser_ahead import cone_indices, nearest_ahead_m

# The lesson's topurg: 1081 beams over 270.25 degrees, 0..30 m (its world file).
FOV = math.radians(270.25)
N = 1081
AMIN, AINC = -FOV / 2, FOV / (N - 1)
FRONT = 540  # the middle beam points straight ahead
CONE = 0.35  # rad
TOL = 1e-12


def scan(hits=None, base=30.0):
    """1081 readings of base metres (30 = nothing hit), with {beam: range} overrides."""
    ranges = [base] * N
    for i, r in (hits or {}).items():
        ranges[i] = r
    return ranges


def ahead(ranges, half=CONE, rmin=0.0, rmax=30.0):
    return nearest_ahead_m(ranges, AMIN, AINC, rmin, rmax, half)


def beam_at(angle):
    return round((angle - AMIN) / AINC)


def test_cone_is_symmetric_about_the_front_beam():
    cone = cone_indices(N, AMIN, AINC, CONE)
    assert FRONT - cone[0] == cone[-1] - FRONT
    assert abs(AMIN + cone[0] * AINC) <= CONE + TOL
    assert abs(AMIN + (cone[0] - 1) * AINC) > CONE
    assert abs(AMIN + (cone[-1] + 1) * AINC) > CONE


def test_cone_edge_beam_counts_despite_rounding():
    # beam 13's angle, -1.0 + 13 * 0.1, is 0.30000000000000004 in floats: still on the edge
    assert -1.0 + 13 * 0.1 > 0.3
    assert list(cone_indices(21, -1.0, 0.1, 0.3)) == list(range(7, 14))


def test_cone_of_a_clockwise_scan():
    # the same beams listed from +1 rad down to -1 rad
    assert list(cone_indices(21, 1.0, -0.1, 0.3)) == list(range(7, 14))


def test_cone_wider_than_the_scan_is_clamped():
    assert list(cone_indices(5, -0.2, 0.1, math.pi)) == list(range(5))


@pytest.mark.parametrize('hits, expected', [
    ({}, math.inf),                                  # nothing in range: 30 m is a miss
    ({FRONT: 0.8}, 0.8),                             # wall straight ahead
    ({FRONT: 0.8, FRONT + 3: 0.6}, 0.6),             # the nearest of several
    ({beam_at(0.34): 0.4}, 0.4),                     # just inside the cone
    ({beam_at(0.36): 0.4}, math.inf),                # just outside: beside the robot
    ({beam_at(-0.36): 0.4, FRONT: 2.0}, 2.0),
    ({FRONT: math.nan}, math.inf),                   # NaN is no reading
    ({FRONT: math.inf}, math.inf),                   # inf is nothing hit
    ({FRONT: 29.999}, 29.999),                       # below range_max: a hit
])
def test_nearest_ahead(hits, expected):
    assert ahead(scan(hits)) == pytest.approx(expected, abs=TOL)


def test_readings_below_range_min_are_invalid():
    assert ahead(scan({FRONT: 0.05, FRONT + 1: 0.3}), rmin=0.1) == pytest.approx(0.3)


@pytest.mark.parametrize('args', [
    (math.nan, AINC, 0.0, 30.0, CONE), (AMIN, 0.0, 0.0, 30.0, CONE),
    (AMIN, math.inf, 0.0, 30.0, CONE), (AMIN, AINC, 0.0, 30.0, 0.0),
    (AMIN, AINC, 0.0, 30.0, -0.1), (AMIN, AINC, 0.0, 30.0, 4.0),
    (AMIN, AINC, 0.0, 30.0, math.nan), (AMIN, AINC, -1.0, 30.0, CONE),
    (AMIN, AINC, 5.0, 5.0, CONE), (AMIN, AINC, 0.0, math.inf, CONE),
    (AMIN, AINC, None, 30.0, CONE),
])
def test_bad_scan_geometry_is_refused(args):
    with pytest.raises(ValueError):
        nearest_ahead_m(scan(), *args)
