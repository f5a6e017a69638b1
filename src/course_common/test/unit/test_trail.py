"""Unit tests of course_common.trail (bounded trails) and course_common.arena's outline."""

import math

import pytest
from course_common.arena import WORLD_SIZE_M, arena_outline
from course_common.trail import Trail, Trails


def test_arena_outline_is_the_closed_world_square():
    s = WORLD_SIZE_M
    assert arena_outline() == [(0.0, 0.0), (s, 0.0), (s, s), (0.0, s), (0.0, 0.0)]
    assert pytest.approx(11.088889, abs=1e-6) == WORLD_SIZE_M


@pytest.mark.parametrize('size', [0, -1.0, math.nan, math.inf, '11'])
def test_arena_outline_rejects_bad_sizes(size):
    with pytest.raises(ValueError, match='arena size'):
        arena_outline(size)


@pytest.mark.parametrize('points, spacing, expected', [
    ([(0, 0), (0.01, 0), (0.1, 0)], 0.05, [(0, 0), (0.1, 0)]),      # too close: skipped
    ([(0, 0), (0, 0), (0, 0)], 0.0, [(0, 0), (0, 0), (0, 0)]),        # spacing 0 keeps all
    ([(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)], 0.5, [(2, 0), (3, 0), (4, 0)]),  # bounded: 3
    ([(5, 5)], 1.0, [(5, 5)]),
])
def test_trail_keeps_spaced_recent_points(points, spacing, expected):
    trail = Trail(3, spacing)
    for x, y in points:
        trail.add(x, y)
    assert trail.points() == expected
    assert len(trail) == len(expected)


def test_trail_add_reports_whether_it_appended():
    trail = Trail(10, 0.1)
    assert trail.add(1.0, 1.0) is True
    assert trail.add(1.05, 1.0) is False
    assert trail.add(1.2, 1.0) is True


@pytest.mark.parametrize('max_points, spacing, message', [
    (1, 0.1, 'trail length'), (2.0, 0.1, 'trail length'), (True, 0.1, 'trail length'),
    (10, -0.1, 'trail spacing'), (10, math.nan, 'trail spacing'), (10, None, 'trail spacing'),
])
def test_trail_rejects_bad_settings(max_points, spacing, message):
    with pytest.raises(ValueError, match=message):
        Trail(max_points, spacing)


@pytest.mark.parametrize('x, y', [(math.nan, 0.0), (0.0, math.inf)])
def test_trail_refuses_non_finite_points(x, y):
    trail = Trail(10, 0.0)
    with pytest.raises(ValueError, match='trail point'):
        trail.add(x, y)
    assert trail.points() == []


def test_trails_of_many_robots_at_once_keep_each_robots_order_past_the_ring():
    trails = Trails(3, 4, 0.5)
    for k in range(10):
        appended = trails.add_all([[k, 0.0], [0.0, k * 0.25], [k, k]])
        assert appended.tolist() == [True, k % 2 == 0, True]
    assert trails.get(0).tolist() == [[6, 0], [7, 0], [8, 0], [9, 0]]     # the last 4
    assert trails.get(1).tolist() == [[0, 0.5], [0, 1.0], [0, 1.5], [0, 2.0]]
    assert trails.held(2) == 4
    trails.clear()
    assert trails.get(2).shape == (0, 2) and trails.add_all([[1.0, 1.0]], [2]).tolist() == [True]
