"""Unit tests of convoy.control: the course's follower law with the wrapped heading error."""
import math

import pytest
from convoy.control import (
    MAX_TURN_WHILE_DRIVING_RADPS,
    Gains,
    distance,
    follow,
)
from course_common.planar import STOP, Pose

TOL = 1e-9  # absolute tolerance for float comparisons: pure arithmetic, no integration
PI = math.pi
G = Gains()  # the course's values: 0.3, 1.35, 1.5 m


def test_defaults_are_the_course_values():
    assert (G.kp_lv, G.kp_av, G.tolerance_m) == (0.3, 1.35, 1.5)


@pytest.mark.parametrize('leader, follower', [
    (Pose(1.0, 1.0, 0.0), Pose(1.0, 1.0, 0.0)),       # same spot
    (Pose(2.4, 1.0, 0.0), Pose(1.0, 1.0, 2.0)),       # 1.4 m away, facing elsewhere
    (Pose(0.0, 1.49, 0.0), Pose(0.0, 0.0, -3.0)),     # just inside
])
def test_inside_tolerance_stops(leader, follower):
    assert follow(leader, follower, G) == STOP


@pytest.mark.parametrize('leader, follower, linear, angular', [
    # Facing the leader, 1.5 m away (the tolerance itself counts as outside: d >= tolerance).
    (Pose(1.5, 0.0, 0.0), Pose(0.0, 0.0, 0.0), 0.3 * 1.5, 0.0),
    # 4 m straight ahead: Kp_lv * d, no turn.
    (Pose(4.0, 3.0, 0.0), Pose(0.0, 3.0, 0.0), 1.2, 0.0),
    # Small error 0.5 rad to the left: 1.35 * 0.5 = 0.675 <= 1, so it drives and turns.
    (Pose(2 * math.cos(0.5), 2 * math.sin(0.5), 0.0), Pose(0.0, 0.0, 0.0),
     0.6, 1.35 * 0.5),
    # Error pi/2 to the right: |w| = 2.12 > 1, so it turns on the spot.
    (Pose(0.0, -3.0, 0.0), Pose(0.0, 0.0, 0.0), 0.0, -1.35 * PI / 2),
])
def test_outside_tolerance_course_law(leader, follower, linear, angular):
    command = follow(leader, follower, G)
    assert command.linear_mps == pytest.approx(linear, abs=TOL)
    assert command.angular_radps == pytest.approx(angular, abs=TOL)


@pytest.mark.parametrize('error_rad', [0.75, 1.0 / 1.35 + 1e-6, 1.2, 3.0, -0.8, -2.5])
def test_no_forward_speed_when_turning_fast(error_rad):
    leader = Pose(5 * math.cos(error_rad), 5 * math.sin(error_rad), 0.0)
    command = follow(leader, Pose(0.0, 0.0, 0.0), G)
    assert abs(command.angular_radps) > MAX_TURN_WHILE_DRIVING_RADPS
    assert command.linear_mps == 0.0


@pytest.mark.parametrize('bearing, theta, expected_error', [
    # Leader just past -pi (behind-left), follower facing just below +pi: 0.2 rad to the left,
    # where the unwrapped course law would turn 2*pi - 0.2 rad to the right.
    (-PI + 0.1, PI - 0.1, 0.2),
    (PI - 0.1, -PI + 0.1, -0.2),
    (-PI + 0.3, 3.0, PI + 0.3 - 3.0),
])
def test_wrap_near_pi_turns_the_short_way(bearing, theta, expected_error):
    leader = Pose(5 * math.cos(bearing), 5 * math.sin(bearing), 0.0)
    command = follow(leader, Pose(0.0, 0.0, theta), G)
    assert command.angular_radps == pytest.approx(1.35 * expected_error, abs=1e-9)
    assert abs(command.angular_radps) < 1.35 * PI / 2


@pytest.mark.parametrize('bad', [float('nan'), float('inf'), -float('inf')])
@pytest.mark.parametrize('field', ['x', 'y', 'theta'])
@pytest.mark.parametrize('who', ['leader', 'follower'])
def test_non_finite_pose_raises(bad, field, who):
    good = {'x': 1.0, 'y': 2.0, 'theta': 0.5}
    broken = Pose(**{**good, field: bad})
    poses = {'leader': Pose(5.0, 5.0, 0.0), 'follower': Pose(**good)}
    poses[who] = broken
    with pytest.raises(ValueError):
        follow(poses['leader'], poses['follower'], G)


@pytest.mark.parametrize('kwargs', [
    {'kp_lv': -0.1}, {'kp_av': float('nan')}, {'tolerance_m': float('inf')},
    {'tolerance_m': -1.0}, {'kp_lv': '0.3'}, {'kp_av': True},
])
def test_bad_gains_raise(kwargs):
    with pytest.raises(ValueError):
        Gains(**kwargs)


def test_custom_gains_apply():
    gains = Gains(kp_lv=1.0, kp_av=0.5, tolerance_m=0.1)
    command = follow(Pose(0.2, 0.0, 0.0), Pose(0.0, 0.0, 0.0), gains)
    assert command.linear_mps == pytest.approx(0.2, abs=TOL)
    assert distance(Pose(3.0, 4.0, 0.0), Pose(0.0, 0.0, 1.0)) == pytest.approx(5.0, abs=TOL)
