"""Unit tests of convoy.path: the autopilot's figure eight and its pure-pursuit tracker."""
import math

import pytest
from convoy.path import Lemniscate, PurePursuit, step_unicycle
from course_common.angles import wrap_angle
from course_common.arena import CENTRE_M, WORLD_SIZE_M
from course_common.planar import Command, Pose

TOL = 1e-9  # absolute tolerance for closed-form comparisons
SAMPLES = 2000
DT_S = 0.016  # turtlesim's fixed tick
PATH = Lemniscate()


def _samples(path, n=SAMPLES):
    return [path.point(2 * math.pi * i / n) for i in range(n + 1)]


def test_default_path_stays_inside_world_with_margin():
    margin_m = 1.0
    assert PATH.fits_in_world(margin_m)
    for x, y in _samples(PATH):
        assert margin_m <= x <= WORLD_SIZE_M - margin_m
        assert margin_m <= y <= WORLD_SIZE_M - margin_m


@pytest.mark.parametrize('path', [PATH, Lemniscate(3.0, 4.0, 2.0, 1.0),
                                  Lemniscate(5.5, 5.5, 5.0, 5.0)])
def test_closed_and_starts_at_centre(path):
    start, end = path.point(0.0), path.point(2 * math.pi)
    assert end == pytest.approx(start, abs=TOL)
    assert start == pytest.approx((path.centre_x, path.centre_y), abs=TOL)


@pytest.mark.parametrize('path', [PATH, Lemniscate(3.0, 4.0, 2.0, 1.0)])
def test_smooth(path):
    # Neighbouring samples are close (continuous) and the heading changes by a small step
    # (no corner), including across the s = 2*pi seam.
    pts = _samples(path)
    step_m = max(math.dist(a, b) for a, b in zip(pts, pts[1:], strict=False))
    assert step_m < 0.05
    headings = [path.heading(2 * math.pi * i / SAMPLES) for i in range(SAMPLES + 1)]
    turn_rad = max(abs(wrap_angle(b - a)) for a, b in zip(headings, headings[1:], strict=False))
    assert turn_rad < 0.05
    assert wrap_angle(headings[-1] - headings[0]) == pytest.approx(0.0, abs=1e-6)


def test_fits_in_world_detects_overflow():
    assert not Lemniscate(half_width=5.2).fits_in_world(0.5)
    assert not Lemniscate(half_height=4.6).fits_in_world(1.0)
    assert not Lemniscate(centre_x=2.0).fits_in_world(0.5)


@pytest.mark.parametrize('kwargs', [
    {'half_width': 0.0}, {'half_height': -1.0}, {'half_width': float('nan')},
    {'centre_x': float('inf')}, {'half_height': '2'},
])
def test_bad_path_raises(kwargs):
    with pytest.raises(ValueError):
        Lemniscate(**kwargs)


@pytest.mark.parametrize('kwargs', [
    {'speed_mps': 0.0}, {'lookahead_m': -1.0}, {'max_turn_radps': float('nan')},
])
def test_bad_pursuit_raises(kwargs):
    with pytest.raises(ValueError):
        PurePursuit(PATH, **kwargs)


def test_pursuit_rejects_non_finite_pose():
    with pytest.raises(ValueError):
        PurePursuit(PATH).command(Pose(float('nan'), 1.0, 0.0))


@pytest.mark.parametrize('start', [
    Pose(CENTRE_M, CENTRE_M, 0.0),   # where turtlesim spawns turtle1
    Pose(CENTRE_M, CENTRE_M, 2.5),   # same spot, facing the other branch
    Pose(8.0, 4.0, -2.0),                        # off the path, facing away
])
def test_pursuit_drives_laps_inside_world(start):
    # Two laps at turtlesim's 16 ms tick: the robot stays near the path, inside the world,
    # and goes round the whole eight (visits both lobes).
    pursuit = PurePursuit(PATH)
    pts = _samples(PATH, 400)
    pose = start
    worst_m = 0.0
    xs = []
    for k in range(6000):
        command = pursuit.command(pose)
        assert abs(command.angular_radps) <= pursuit.max_turn_radps + TOL
        pose = step_unicycle(pose, command, DT_S)
        xs.append(pose.x)
        if k > 500 and k % 10 == 0:  # after settling onto the path; every 10th tick
            worst_m = max(worst_m, min(math.hypot(x - pose.x, y - pose.y) for x, y in pts))
        assert 0.5 <= pose.x <= WORLD_SIZE_M - 0.5 and 0.5 <= pose.y <= WORLD_SIZE_M - 0.5
    assert worst_m < 0.2
    assert min(xs) < PATH.centre_x - 0.9 * PATH.half_width
    assert max(xs) > PATH.centre_x + 0.9 * PATH.half_width


def test_step_unicycle_turns_then_moves():
    pose = step_unicycle(Pose(1.0, 1.0, 0.0), Command(1.0, math.pi / 2 / DT_S), DT_S)
    assert (pose.x, pose.y, pose.theta) == pytest.approx((1.0, 1.0 + DT_S, math.pi / 2), abs=TOL)
