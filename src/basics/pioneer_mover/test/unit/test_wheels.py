"""Unit tests of pioneer_mover.wheels: the lab's wheel speeds, the Pioneer's limits, and the
body velocity Stage is given."""
import math

import pytest
from pioneer_mover.wheels import (
    DEFAULT_MAX_TURN_RADPS,
    DEFAULT_MAX_WHEEL_MPS,
    TRACK_WIDTH_M,
    Drive,
    WheelLimits,
    body_velocity,
    check_track_width,
    drive,
    limit_wheels,
    wheel_speeds,
)

TOL = 1e-12  # a few additions and one division each
WIDE = WheelLimits(100.0, 100.0)  # limits that never bind


def test_the_labs_and_stages_figures():
    assert TRACK_WIDTH_M == 0.33
    assert DEFAULT_MAX_WHEEL_MPS == 0.5  # pioneer.inc: velocity_bounds x in [-0.5, 0.5]
    assert math.pi / 2 == pytest.approx(DEFAULT_MAX_TURN_RADPS, abs=TOL)  # [-90, 90] deg/s


@pytest.mark.parametrize('v, w, expected', [
    (0.5, 0.0, (0.5, 0.5)),                      # the teleop's up arrow, a quarter of 2.0
    (0.0, 0.5, (-0.0825, 0.0825)),               # left arrow: L/2 = 0.165 m
    (0.0, -0.5, (0.0825, -0.0825)),
    (0.2, 1.0, (0.2 - 0.165, 0.2 + 0.165)),
    (-0.3, 0.0, (-0.3, -0.3)),
    (0.0, 0.0, (0.0, 0.0)),
])
def test_wheel_speeds_are_the_labs(v, w, expected):
    assert wheel_speeds(v, w) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize('v, w', [(0.5, 0.0), (0.0, 0.5), (0.2, -1.0), (-0.4, 0.3), (1, 2)])
def test_body_velocity_undoes_wheel_speeds(v, w):
    assert body_velocity(*wheel_speeds(v, w)) == pytest.approx((v, w), abs=TOL)


@pytest.mark.parametrize('wheels, expected', [
    ((0.3, 0.4), (0.3, 0.4)),                    # within both limits: unchanged
    ((0.5, 0.5), (0.5, 0.5)),                    # at the limit: unchanged
    ((2.0, 2.0), (0.5, 0.5)),                    # straight ahead at 2 m/s: 0.5 m/s
    ((-2.0, -1.0), (-0.5, -0.25)),               # backwards: the faster wheel at the limit
    ((0.4, 1.0), (0.2, 0.5)),                    # the ratio (the path) kept
    # turning on the spot at 3 rad/s: wheels +-0.495 are within 0.5 m/s, the turn is not
    ((-0.495, 0.495), (-0.165 * math.pi / 2, 0.165 * math.pi / 2)),
])
def test_limit_wheels(wheels, expected):
    assert limit_wheels(*wheels) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize('v, w', [(3.0, 0.0), (1.2, 5.236), (0.0, -20.0), (-1.0, 0.7), (0.4, 4.0)])
def test_drive_stays_within_the_limits_on_the_asked_path(v, w):
    got = drive(v, w)
    assert got.limited
    assert max(abs(s) for s in got.wheels_mps) <= DEFAULT_MAX_WHEEL_MPS + TOL
    assert abs(got.angular_radps) <= DEFAULT_MAX_TURN_RADPS + TOL
    # one factor for both: the same curvature (w / v), the same direction of travel and turn
    scale = got.wheels_mps[0] / got.asked_mps[0]
    assert 0.0 < scale < 1.0
    assert got.wheels_mps[1] == pytest.approx(scale * got.asked_mps[1], abs=TOL)
    assert (got.linear_mps, got.angular_radps) == pytest.approx((scale * v, scale * w), abs=TOL)


def test_drive_within_the_limits_is_the_command():
    got = drive(0.3, -0.5)
    assert got == Drive((0.3 + 0.0825, 0.3 - 0.0825), (0.3 + 0.0825, 0.3 - 0.0825),
                        got.linear_mps, got.angular_radps)
    assert not got.limited
    assert (got.linear_mps, got.angular_radps) == pytest.approx((0.3, -0.5), abs=TOL)


def test_drive_with_other_limits_and_track():
    got = drive(1.0, 0.0, WheelLimits(max_wheel_mps=1.2, max_turn_radps=math.radians(300)),
                track_m=0.4)
    assert not got.limited and got.linear_mps == 1.0
    got = drive(0.0, 4.0, WIDE, track_m=0.5)
    assert got.wheels_mps == pytest.approx((-1.0, 1.0), abs=TOL)


@pytest.mark.parametrize('call', [
    lambda: wheel_speeds(math.nan, 0.0),
    lambda: wheel_speeds(0.0, math.inf),
    lambda: body_velocity(-math.inf, 0.0),
    lambda: limit_wheels(0.1, math.nan),
    lambda: drive(math.nan, math.nan),
    lambda: drive('0.5', 0.0),
])
def test_non_finite_is_refused(call):
    with pytest.raises(ValueError, match='non-finite component: expected finite numbers'):
        call()


@pytest.mark.parametrize('track', [0, -0.33, math.nan, math.inf, True, '0.33'])
def test_bad_track_width(track):
    with pytest.raises(ValueError, match=r'track width = .*: expected a finite number > 0 \(m\)'):
        check_track_width(track)
    with pytest.raises(ValueError, match='track width'):
        drive(0.1, 0.1, track_m=track)


@pytest.mark.parametrize('kwargs, words', [
    ({'max_wheel_mps': 0.0}, 'max_wheel_mps = 0.0: expected a finite number > 0'),
    ({'max_wheel_mps': -0.5}, 'max_wheel_mps = -0.5: expected a finite number > 0'),
    ({'max_turn_radps': math.nan}, 'max_turn_radps = nan: expected a finite number > 0'),
    ({'max_turn_radps': math.inf}, 'max_turn_radps = inf: expected a finite number > 0'),
])
def test_bad_limits(kwargs, words):
    with pytest.raises(ValueError, match=words):
        WheelLimits(**kwargs)
