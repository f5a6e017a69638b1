"""Unit tests of course_common.angles: the lessons' wrap into [-pi, pi), yaw of a quaternion."""
import math

import pytest
from course_common.angles import wrap_angle, yaw_from_quaternion

TOL = 1e-9  # rad: pure arithmetic; the wrap adds at most a few ulps of 2 pi per turn
PI = math.pi


@pytest.mark.parametrize('angle, expected', [
    (0.0, 0.0),
    (1.0, 1.0),
    (-1.0, -1.0),
    (3, 3.0),                        # ints are angles too
    (PI, -PI),                       # half-open: +pi maps to -pi
    (-PI, -PI),
    (PI - 1e-12, PI - 1e-12),        # just inside stays
    (3 * PI / 2, -PI / 2),
    (-3 * PI / 2, PI / 2),
    (2 * PI, 0.0),
    (6.0, 6.0 - 2 * PI),             # the lab's beta of 6.0 rad is a 0.28 rad turn the other way
    (-6.0, 2 * PI - 6.0),
    (7 * PI + 0.25, -PI + 0.25),
    (-100.0, -100.0 + 32 * PI),
    (1e6, 1e6 - 2 * PI * round(1e6 / (2 * PI))),
])
def test_wrap_angle(angle, expected):
    wrapped = wrap_angle(angle)
    assert wrapped == pytest.approx(expected, abs=TOL)
    assert -PI <= wrapped < PI


@pytest.mark.parametrize('angle', [-PI - 1e-17, -PI - 5e-16, 3 * PI, -3 * PI, 1e300, -1e300])
def test_result_stays_in_the_half_open_interval(angle):
    wrapped = wrap_angle(angle)
    assert -PI <= wrapped < PI


@pytest.mark.parametrize('target, heading, turn', [
    (0.5, 0.0, 0.5),                 # target to the left: positive (counter-clockwise)
    (-0.5, 0.0, -0.5),
    (-3.0, 3.0, 2 * PI - 6.0),       # across the seam: the short way, left
    (3.0, -3.0, 6.0 - 2 * PI),       # across the seam: the short way, right
])
def test_wrapped_difference_is_the_short_turn(target, heading, turn):
    assert wrap_angle(target - heading) == pytest.approx(turn, abs=TOL)


@pytest.mark.parametrize('angle', [math.nan, math.inf, -math.inf, True, '1.0', None])
def test_refuses_what_is_not_a_finite_number(angle):
    with pytest.raises(ValueError, match='expected a finite number'):
        wrap_angle(angle)


@pytest.mark.parametrize('yaw', [0.0, 0.3, -0.3, PI / 2, -PI / 2, 3.0, -3.0, PI - 1e-9])
def test_yaw_from_quaternion_of_a_planar_rotation(yaw):
    # a rotation about z by yaw: (0, 0, sin(yaw/2), cos(yaw/2)), as Stage's odometry sends it
    assert yaw_from_quaternion(0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)) \
        == pytest.approx(yaw, abs=TOL)


def test_yaw_from_quaternion_of_the_negated_quaternion_is_the_same():
    half = 0.6 / 2
    assert yaw_from_quaternion(0.0, 0.0, -math.sin(half), -math.cos(half)) \
        == pytest.approx(0.6, abs=TOL)  # -q is the same rotation


@pytest.mark.parametrize('q', [(0.0, 0.0, math.nan, 1.0), (0.0, 0.0, 0.0, math.inf),
                               (None, 0.0, 0.0, 1.0), (0.0, 0.0, True, 1.0)])
def test_yaw_from_quaternion_rejects_non_finite(q):
    with pytest.raises(ValueError):
        yaw_from_quaternion(*q)
