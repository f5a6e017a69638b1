"""Unit tests of closed_loop_turtle.go_to_goal: the lab's two-phase law with our fixes."""
import math

import pytest
from closed_loop_turtle.go_to_goal import (
    DEFAULT_MAX_ANGULAR_RADPS,
    Gains,
    GoalError,
    Limits,
    Phase,
    Tolerances,
    check_goal,
    check_pose,
    heading_error,
    limit,
    position_error,
    step,
)
from course_common.angles import wrap_angle
from course_common.arena import WORLD_SIZE_M
from course_common.planar import STOP, Command, Pose

TOL = 1e-9  # pure arithmetic, no integration
PI = math.pi
G = Gains()
UNLIMITED = Limits(1e9, 1e9)  # to check the law's own numbers
DT_S = 0.016  # turtlesim's tick


def test_defaults_are_the_labs():
    assert (G.k_rho, G.k_alpha, G.k_beta) == (3.14, 5.0, -3.0)
    assert (Tolerances().position_m, Tolerances().heading_rad) == (0.1, 0.05)
    assert Limits().max_linear_mps == 1.2
    assert Limits().max_angular_radps == DEFAULT_MAX_ANGULAR_RADPS
    assert math.isclose(DEFAULT_MAX_ANGULAR_RADPS, 5.235987756, abs_tol=1e-9)  # 300 deg/s


@pytest.mark.parametrize('pose, goal, rho, alpha', [
    (Pose(0, 0, 0), Pose(3, 4, 0), 5.0, math.atan2(4, 3)),
    (Pose(5, 5, 0), Pose(2, 5, 0), 3.0, -PI),                # straight behind: -pi (half-open)
    (Pose(5, 5, 3.0), Pose(5, 6, 0), 1.0, PI / 2 - 3.0),
    (Pose(5, 5, -3.0), Pose(4, 5, 0), 1.0, wrap_angle(PI + 3.0)),  # across the seam: short way
])
def test_position_error(pose, goal, rho, alpha):
    assert position_error(pose, goal) == pytest.approx((rho, alpha), abs=TOL)


@pytest.mark.parametrize('theta, theta_g, beta', [
    (0.0, 0.0, 0.0),
    (1.0, 0.5, 0.5),
    (3.0, -3.0, 6.0 - 2 * PI),    # the lab's beta is 6.0: it turns 6 rad the long way
    (-3.0, 3.0, 2 * PI - 6.0),
    (PI / 2, -PI / 2, -PI),
])
def test_heading_error_is_wrapped(theta, theta_g, beta):
    assert heading_error(Pose(1, 1, theta), Pose(1, 1, theta_g)) == pytest.approx(beta, abs=TOL)


@pytest.mark.parametrize('command, limits, expected', [
    (Command(0.5, 1.0), Limits(1.2, 5.0), Command(0.5, 1.0)),     # within: unchanged
    (Command(2.4, 1.0), Limits(1.2, 5.0), Command(1.2, 1.0)),     # v clipped, w kept
    (Command(1.0, -10.0), Limits(1.2, 5.0), Command(1.0, -5.0)),  # w clipped, sign kept
    (Command(-3.6, 30.0), Limits(1.2, 5.0), Command(-1.2, 5.0)),  # both clipped
    (Command(1.2, -5.0), Limits(1.2, 5.0), Command(1.2, -5.0)),   # on the limits: unchanged
    (STOP, Limits(1.2, 5.0), STOP),
])
def test_limit_clips_each_speed(command, limits, expected):
    got = limit(command, limits)
    assert (got.linear_mps, got.angular_radps) == pytest.approx(
        (expected.linear_mps, expected.angular_radps), abs=TOL)


# (phase, pose, goal) -> (phase, v, w, reached_position, reached_orientation), unlimited.
@pytest.mark.parametrize('phase, pose, goal, expected', [
    # driving: v = k_rho rho, w = k_alpha alpha
    (Phase.POSITION, Pose(0, 0, 0), Pose(3, 4, 1), (Phase.POSITION, 3.14 * 5, 5 * math.atan2(4, 3),
                                                    False, False)),
    # just inside the position tolerance: falls through to turning, in the same step
    (Phase.POSITION, Pose(1, 1, 0), Pose(1.09, 1, 1), (Phase.ORIENTATION, 0.0, -3 * (0 - 1),
                                                       True, False)),
    # inside both tolerances at once: both reached in one step
    (Phase.POSITION, Pose(1, 1, 0.5), Pose(1.05, 1, 0.52), (Phase.ARRIVED, 0.0, 0.0, True, True)),
    # turning: w = k_beta wrap(theta - theta_g), the short way across the seam
    (Phase.ORIENTATION, Pose(1, 1, 3.0), Pose(1, 1, -3.0),
     (Phase.ORIENTATION, 0.0, -3 * (6.0 - 2 * PI), False, False)),
    (Phase.ORIENTATION, Pose(1, 1, 1.0), Pose(1, 1, 1.04), (Phase.ARRIVED, 0.0, 0.0, False, True)),
    # orientation never goes back to position, even if the robot was pushed away
    (Phase.ORIENTATION, Pose(3, 3, 0.0), Pose(1, 1, 1.0), (Phase.ORIENTATION, 0.0, 3.0,
                                                           False, False)),
    (Phase.ARRIVED, Pose(0, 0, 0), Pose(5, 5, 0), (Phase.ARRIVED, 0.0, 0.0, False, False)),
])
def test_step(phase, pose, goal, expected):
    got = step(phase, pose, goal, G, Tolerances(), UNLIMITED)
    assert got.phase is expected[0]
    assert (got.command.linear_mps, got.command.angular_radps) == pytest.approx(expected[1:3],
                                                                                abs=TOL)
    assert (got.reached_position, got.reached_orientation) == expected[3:]


def test_step_applies_the_limits():
    got = step(Phase.POSITION, Pose(0, 0, 0), Pose(3, 4, 1), G, Tolerances(), Limits(1.2, 5.0))
    assert abs(got.command.linear_mps) <= 1.2 + TOL
    assert abs(got.command.angular_radps) <= 5.0 + TOL
    assert got.command.linear_mps == 1.2  # 3.14 * 5 m clipped
    assert got.command.angular_radps == pytest.approx(5 * math.atan2(4, 3), abs=TOL)  # < 5


@pytest.mark.parametrize('kwargs, words', [
    ({'k_rho': 0.0}, 'k_rho must be > 0'),
    ({'k_beta': 1.0}, 'k_beta must be < 0'),
    ({'k_alpha': 3.0}, 'k_alpha must be greater than k_rho'),
    ({'k_rho': math.nan}, 'k_rho = nan: expected a finite number'),
    ({'k_alpha': '5'}, "k_alpha = '5': expected a finite number"),
    ({'k_beta': True}, 'k_beta = True: expected a finite number'),
])
def test_gains_check_the_labs_conditions(kwargs, words):
    with pytest.raises(ValueError, match=words):
        Gains(**kwargs)


@pytest.mark.parametrize('cls, kwargs, words', [
    (Tolerances, {'position_m': 0.0}, 'position_m = 0.0: expected a finite number > 0'),
    (Tolerances, {'heading_rad': -0.1}, 'heading_rad = -0.1: expected a finite number > 0'),
    (Limits, {'max_linear_mps': math.inf}, 'max_linear_mps = inf: expected a finite number > 0'),
    (Limits, {'max_angular_radps': 0}, 'max_angular_radps = 0: expected a finite number > 0'),
])
def test_bad_tolerances_and_limits(cls, kwargs, words):
    with pytest.raises(ValueError, match=words):
        cls(**kwargs)


@pytest.mark.parametrize('goal, words', [
    (Pose(math.nan, 5, 0), 'non-finite'),
    (Pose(5, 5, math.inf), 'non-finite'),
    (Pose(-0.1, 5, 0), 'outside the world'),
    (Pose(5, WORLD_SIZE_M + 0.01, 0), 'outside the world'),
    (Pose(20, 20, 0), 'outside the world'),
])
def test_bad_goals_are_refused(goal, words):
    with pytest.raises(GoalError, match=words):
        check_goal(goal)


@pytest.mark.parametrize('goal', [Pose(0, 0, 0), Pose(WORLD_SIZE_M, WORLD_SIZE_M, 3.0),
                                  Pose(5, 5, -10.0)])
def test_goals_inside_the_world_pass(goal):
    assert check_goal(goal) == goal


def test_non_finite_pose_is_refused():
    with pytest.raises(GoalError, match='non-finite'):
        check_pose(Pose(1, math.nan, 0))
    assert check_pose(Pose(1, 2, 3)) == Pose(1, 2, 3)


def _simulate(pose, goal, max_ticks=5000):
    """turtlesim's update (heading first, then position, dt 0.016 s) under the law, one step a
    tick, with the default limits. Returns (final pose, ticks, total turn in rad, the path's
    bounding box (min x, max x, min y, max y))."""
    phase, turned = Phase.POSITION, 0.0
    box = [pose.x, pose.x, pose.y, pose.y]
    for tick in range(max_ticks):
        result = step(phase, pose, goal)
        phase = result.phase
        if phase is Phase.ARRIVED:
            return pose, tick, turned, tuple(box)
        v, w = result.command.linear_mps, result.command.angular_radps
        theta = wrap_angle(pose.theta + w * DT_S)
        turned += abs(w) * DT_S
        pose = Pose(pose.x + v * math.cos(theta) * DT_S, pose.y + v * math.sin(theta) * DT_S,
                    theta)
        box = [min(box[0], pose.x), max(box[1], pose.x), min(box[2], pose.y), max(box[3], pose.y)]
    raise AssertionError('no arrival after %d ticks: %r' % (max_ticks, pose))


# From the world's centre heading +x: ahead, behind, beside, and a goal heading across the seam.
@pytest.mark.parametrize('start, goal', [
    (Pose(5.54, 5.54, 0.0), Pose(9.0, 5.54, 0.0)),
    (Pose(5.54, 5.54, 0.0), Pose(2.0, 5.0, PI / 2)),       # behind the robot
    (Pose(5.54, 5.54, 0.0), Pose(5.54, 5.84, 0.0)),        # 0.3 m to the left: a tight turn
    (Pose(2.0, 5.0, 3.0), Pose(2.0, 5.0, -3.0)),           # turn only, across the seam
    (Pose(1.0, 1.0, -PI / 2), Pose(10.0, 10.0, -3.1)),
    (Pose(8.0, 8.5, 1.0), Pose(1.0, 1.0, 0.0)),            # far behind: the lab's law leaves
    (Pose(2.5, 5.0, -3.0), Pose(8.0, 8.5, 1.0)),           # the world on these two
])
def test_the_law_arrives_within_tolerance_inside_the_world(start, goal):
    pose, _, _, box = _simulate(start, goal)
    rho, _ = position_error(pose, goal)
    assert rho < 0.1
    assert abs(heading_error(pose, goal)) < 0.05
    min_x, max_x, min_y, max_y = box
    assert min(min_x, min_y) >= 0.0
    assert max(max_x, max_y) <= WORLD_SIZE_M


def test_a_heading_change_across_the_seam_turns_the_short_way():
    # theta 3.0 -> -3.0: the short way is 0.283 rad; the lab's unwrapped beta turns 6.0 rad.
    _, _, turned, _ = _simulate(Pose(2.0, 5.0, 3.0), Pose(2.0, 5.0, -3.0))
    assert turned < 2 * PI - 6.0 + 0.05
