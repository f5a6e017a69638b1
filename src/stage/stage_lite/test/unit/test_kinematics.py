"""Stage's velocity step, clamping and footprint geometry."""
import math

import numpy as np
import pytest
from stage_lite.kinematics import (
    clamp_command,
    euler_step,
    rect_corners,
    rect_gap,
    rect_samples,
    z_overlap,
)

TOL = 1e-12  # metres / radians: closed-form arithmetic

BOUNDS = (-1.0, 1.0, -1.0, 1.0, -math.pi / 2, math.pi / 2)


@pytest.mark.parametrize('pose, cmd, dt, expected', [
    ((0, 0, 0), (0.2, 0, 0), 0.1, (0.02, 0, 0)),
    # translation rotated by the OLD heading, then the yaw added (not an arc)
    ((1, 2, math.pi / 2), (1.0, 0, 1.0), 0.1, (1, 2.1, math.pi / 2 + 0.1)),
    ((0, 0, 0), (1.0, 0, math.pi), 0.5, (0.5, 0, -math.pi / 2 - math.pi)),
    ((0, 0, math.pi / 2), (0, 0.5, 0), 1.0, (-0.5, 0, math.pi / 2)),   # omni sideways
])
def test_body_frame_euler(pose, cmd, dt, expected):
    x, y, a = euler_step(pose, cmd, dt)
    ex, ey, ea = expected
    assert (x, y) == pytest.approx((ex, ey), abs=TOL)
    assert math.remainder(a - ea, 2 * math.pi) == pytest.approx(0.0, abs=TOL)


@pytest.mark.parametrize('cmd, drive, expected', [
    ((0.2, 0.3, 0.1), 'diff', (0.2, 0.0, 0.1)),
    ((0.2, 0.3, 0.1), 'omni', (0.2, 0.3, 0.1)),
    ((5.0, -5.0, 9.0), 'omni', (1.0, -1.0, math.pi / 2)),
    ((-5.0, 0.0, -9.0), 'diff', (-1.0, 0.0, -math.pi / 2)),
])
def test_clamp(cmd, drive, expected):
    assert clamp_command(*cmd, BOUNDS, drive) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_command_raises(bad):
    with pytest.raises(ValueError, match='finite'):
        clamp_command(bad, 0.0, 0.0, BOUNDS, 'diff')
    with pytest.raises(ValueError, match='angular.z'):
        clamp_command(0.0, 0.0, bad, BOUNDS, 'diff')


def test_rect_corners_and_gap():
    a = rect_corners(0, 0, 0, 2, 2)
    assert a.min(axis=0) == pytest.approx((-1, -1)) and a.max(axis=0) == pytest.approx((1, 1))
    assert rect_gap(a, rect_corners(3.5, 0, 0, 2, 2)) == pytest.approx(1.5, abs=TOL)
    assert rect_gap(a, rect_corners(1.5, 0, 0.3, 2, 2)) < 0
    diag = rect_corners(3, 3, math.pi / 4, 2, 2)   # a diamond: its edge x + y = 6 - sqrt2 faces a
    assert rect_gap(a, diag) == pytest.approx(2 * math.sqrt(2) - 1, abs=1e-9)


def test_rect_samples_spacing_and_edges():
    xs, ys = rect_samples(0, 0, 0, 0.35, 0.35, 0.02)
    assert xs.min() == pytest.approx(-0.175) and xs.max() == pytest.approx(0.175)
    assert np.diff(np.unique(np.round(xs, 9))).max() <= 0.02 + 1e-12


@pytest.mark.parametrize('a, b, expected', [
    ((0, 0.25), (0, 0.25), True), ((0, 0.25), (0.25, 0.5), False),
    ((0, 0.5), (0.2, 0.3), True), ((0.3, 0.5), (0, 0.25), False)])
def test_z_overlap(a, b, expected):
    assert z_overlap(a, b) is expected
