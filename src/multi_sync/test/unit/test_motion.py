"""Unit tests for multi_sync.motion: the wall bumper, teammates' positions and the layout."""
import math

import pytest
from multi_sync.motion import (
    WORLD_SIZE_M,
    DriveLimits,
    TeamPositions,
    decide,
    distance_to_wall,
    team_layout,
)

# Distances come from a few float operations: 1e-9 m is far below anything that matters.
TOL = 1e-9
W = WORLD_SIZE_M


def test_world_is_turtlesims():
    size = W
    assert size == pytest.approx(11.088889, abs=1e-6)


@pytest.mark.parametrize('x, y, theta, expected', [
    (5.0, 5.0, 0.0, W - 5.0),                    # heading +x
    (5.0, 5.0, math.pi, 5.0),                    # heading -x
    (5.0, 2.0, math.pi / 2, W - 2.0),            # heading +y
    (5.0, 2.0, -math.pi / 2, 2.0),               # heading -y
    (1.0, 1.0, math.pi / 4, (W - 1.0) * math.sqrt(2)),  # diagonal: corner
    (10.0, 1.0, math.pi / 4, (W - 10.0) * math.sqrt(2)),  # diagonal: right wall first
    (W, 5.0, 0.0, 0.0),                          # on the wall it heads into
    (W + 1.0, 5.0, 0.0, 0.0),                    # beyond it: clamped to 0
    (0.0, 5.0, 0.0, W),                          # on the wall behind it
])
def test_distance_to_wall(x, y, theta, expected):
    assert distance_to_wall(x, y, theta) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize('args', [
    (math.nan, 1.0, 0.0), (1.0, math.inf, 0.0), (1.0, 1.0, None), (1.0, 1.0, 0.0, 0.0),
    (1.0, 1.0, 0.0, -5.0), (True, 1.0, 0.0),
])
def test_distance_to_wall_rejects_bad_input(args):
    with pytest.raises(ValueError):
        distance_to_wall(*args)


LIMITS = DriveLimits(speed_mps=0.2, stop_distance_m=0.5, min_gap_m=1.0)


def decide_in_arena(x, y, theta, limits=LIMITS, team=None):
    """decide() as move_robot calls it on turtlesim: the free distance is the wall's."""
    return decide(x, y, theta, distance_to_wall(x, y, theta), limits, team)


@pytest.mark.parametrize('x, theta, linear, reason', [
    (5.0, 0.0, 0.2, 'clear'),
    (W - 0.51, 0.0, 0.2, 'clear'),
    (W - 0.5, 0.0, 0.0, 'wall'),       # exactly the stop distance: stop
    (W - 0.2, 0.0, 0.0, 'wall'),
    (W - 0.2, math.pi, 0.2, 'clear'),  # the wall is behind: drive away from it
])
def test_bumper(x, theta, linear, reason):
    decision = decide_in_arena(x, 5.0, theta)
    assert decision.linear_mps == pytest.approx(linear, abs=TOL)
    assert decision.reason == reason


@pytest.mark.parametrize('ahead, linear, reason', [
    (math.inf, 0.2, 'clear'),   # the laser sees nothing in range
    (0.51, 0.2, 'clear'),
    (0.5, 0.0, 'wall'),         # what the laser sees is at the stop distance: stop
    (0.0, 0.0, 'wall'),
])
def test_bumper_on_a_sensor_distance(ahead, linear, reason):
    decision = decide(-11.5, 23.5, 0.0, ahead, LIMITS)
    assert (decision.linear_mps, decision.reason) == (pytest.approx(linear, abs=TOL), reason)
    assert decision.ahead_m == ahead


@pytest.mark.parametrize('ahead', [0.0, 0.075, 0.3])
def test_zero_stop_distance_turns_the_bumper_off(ahead):
    # the lesson's robot: straight on until the simulator stops it
    lesson = DriveLimits(speed_mps=0.2, stop_distance_m=0.0, min_gap_m=0.0)
    team = _team(0, (1, 0.3, 0.0))
    assert decide(0.0, 0.0, 0.0, ahead, lesson, team).reason == 'clear'


@pytest.mark.parametrize('ahead', [math.nan, -0.1, -math.inf, None, True])
def test_bad_sensor_distance_is_refused(ahead):
    with pytest.raises(ValueError):
        decide(0.0, 0.0, 0.0, ahead, LIMITS)


@pytest.mark.parametrize('kwargs', [
    {'speed_mps': 0.0}, {'speed_mps': -0.2}, {'speed_mps': math.nan},
    {'stop_distance_m': -0.1}, {'stop_distance_m': 6.0}, {'min_gap_m': -1.0},
    {'world_size_m': math.inf}, {'world_size_m': 0.0},
])
def test_drive_limits_reject_bad_values(kwargs):
    with pytest.raises(ValueError):
        DriveLimits(**kwargs)


def test_on_stage_no_square_bounds_the_bumper():
    # world_size_m None: Stage's laser measures what is ahead; 6 m is beyond turtlesim's half
    assert DriveLimits(stop_distance_m=6.0, world_size_m=None).stop_distance_m == 6.0
    with pytest.raises(ValueError):
        DriveLimits(stop_distance_m=math.nan, world_size_m=None)


def _team(own_id, *mates):
    team = TeamPositions(own_id)
    for robot_id, x, y in mates:
        team.update(robot_id, x, y, 0.0, 1.0)
    return team


@pytest.mark.parametrize('mates, expected_id, expected_d', [
    ([], None, None),
    ([(1, 3.0, 5.0)], 1, 2.0),
    ([(1, 3.0, 5.0), (2, 5.0, 6.5), (3, 9.0, 9.0)], 2, 1.5),
    ([(0, 5.0, 5.1), (1, 8.0, 5.0)], 1, 3.0),  # own id 0: its own position is ignored
])
def test_nearest_teammate(mates, expected_id, expected_d):
    nearest = _team(0, *mates).nearest(5.0, 5.0)
    if expected_id is None:
        assert nearest is None
    else:
        assert nearest[0].robot_id == expected_id
        assert nearest[1] == pytest.approx(expected_d, abs=TOL)


@pytest.mark.parametrize('mate, theta, blocked', [
    ((1, 5.8, 5.0), 0.0, True),          # 0.8 m ahead: too close
    ((1, 6.2, 5.0), 0.0, False),         # 1.2 m ahead: far enough
    ((1, 4.2, 5.0), 0.0, False),         # 0.8 m behind: not in the way
    ((1, 5.0, 5.5), 0.0, False),         # exactly beside: not ahead
    ((1, 5.5, 5.5), 0.0, True),          # ahead and to the side, 0.71 m
    ((1, 4.2, 5.0), math.pi, True),      # turned round: now it is ahead
])
def test_teammate_blocking(mate, theta, blocked):
    team = _team(0, mate)
    decision = decide_in_arena(5.0, 5.0, theta, team=team)
    assert (decision.reason == 'teammate') == blocked
    assert decision.linear_mps == pytest.approx(0.0 if blocked else 0.2, abs=TOL)
    if blocked:
        assert decision.teammate_id == 1


def test_wall_wins_over_teammate_and_zero_gap_disables():
    team = _team(0, (1, 10.6, 5.0))
    assert decide_in_arena(10.7 - 0.2, 5.0, 0.0, team=team).reason == 'teammate'
    assert decide_in_arena(W - 0.3, 5.0, 0.0, team=team).reason == 'wall'
    no_gap = DriveLimits(speed_mps=0.2, stop_distance_m=0.5, min_gap_m=0.0)
    assert decide_in_arena(10.3, 5.0, 0.0, no_gap, team).reason == 'clear'


def test_positions_keep_the_latest_message_and_ignore_own():
    team = TeamPositions(2)
    assert team.update(1, 1.0, 1.0, 0.0, 5.0)
    assert team.update(1, 2.0, 1.0, 0.0, 6.0)
    assert not team.update(2, 3.0, 3.0, 0.0, 7.0)  # own position
    assert [(m.robot_id, m.x) for m in team.teammates()] == [(1, 2.0)]
    # robot 1 restarted on sim time after running on wall time: its stamps start again low,
    # and its new positions must replace the old run's (a ghost would block its followers)
    assert team.update(1, 2.5, 1.0, 0.0, 0.3)
    assert [(m.robot_id, m.x, m.stamp_s) for m in team.teammates()] == [(1, 2.5, 0.3)]


@pytest.mark.parametrize('args', [
    (20, 1.0, 1.0, 0.0, 1.0), (-1, 1.0, 1.0, 0.0, 1.0), (1, math.nan, 1.0, 0.0, 1.0),
    (1, 1.0, 1.0, math.inf, 1.0), (1, 1.0, 1.0, 0.0, math.nan),
])
def test_positions_reject_bad_input(args):
    with pytest.raises(ValueError):
        TeamPositions(0).update(*args)


@pytest.mark.parametrize('own_id', [20, -1, 1.0, None])
def test_positions_reject_bad_own_id(own_id):
    with pytest.raises(ValueError):
        TeamPositions(own_id)


def test_blocking_rejects_negative_gap():
    with pytest.raises(ValueError):
        TeamPositions(0).blocking(1.0, 1.0, 0.0, -1.0)


def test_layout_first_four_are_the_lessons_group():
    # Stage: (-11.5, 23.5), (-13.5, 23.5), (-11.5, 21.5), (-13.5, 21.5), shifted so robot 0
    # is turtle1 in the centre of turtlesim's world.
    c = W / 2
    expected = [(c, c), (c - 2, c), (c, c - 2), (c - 2, c - 2)]
    got = [(x, y) for x, y, _ in team_layout(4)]
    assert got == [pytest.approx(p, abs=TOL) for p in expected]


@pytest.mark.parametrize('size', [1, 4, 5, 13, 20])
def test_layout_fits_world_is_distinct_and_keeps_spacing(size):
    layout = team_layout(size)
    assert len(layout) == size
    assert team_layout(size) == team_layout(20)[:size]  # growing the team keeps places
    for x, y, theta in layout:
        assert 1.0 < x < W - 3.0 and 1.0 < y < W - 1.0
        assert theta == 0.0
    for i, a in enumerate(layout):
        for b in layout[i + 1:]:
            assert math.hypot(a[0] - b[0], a[1] - b[1]) >= 2.0 - TOL
    # every robot starts clear of the walls and of the min gap of its teammates
    for i, (x, y, theta) in enumerate(layout):
        team = TeamPositions(i)
        for j, (mx, my, _) in enumerate(layout):
            team.update(j, mx, my, 0.0, 0.0)
        assert decide_in_arena(x, y, theta, team=team).reason == 'clear'


@pytest.mark.parametrize('size', [0, 21, 4.0, None, True])
def test_layout_rejects_bad_size(size):
    with pytest.raises(ValueError):
        team_layout(size)
