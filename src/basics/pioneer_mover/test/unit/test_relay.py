"""Unit tests of pioneer_mover.relay: the quarter-speed command and the Pose2D conversion."""
import math

import pytest
from pioneer_mover.relay import DEFAULT_DIVISOR, check_divisor, pose2d_fields, scale_twist

TOL = 1e-12  # pure arithmetic: a division each


def test_default_is_the_labs_quarter():
    assert DEFAULT_DIVISOR == 4.0


@pytest.mark.parametrize('values, divisor, expected', [
    ((2.0, 0, 0, 0, 0, 0), 4, (0.5, 0, 0, 0, 0, 0)),          # teleop's up arrow
    ((-2.0, 0, 0, 0, 0, 0), 4, (-0.5, 0, 0, 0, 0, 0)),        # down arrow
    ((0, 0, 0, 0, 0, 2.0), 4, (0, 0, 0, 0, 0, 0.5)),          # left arrow
    ((1.0, 0.4, 0.2, 0.1, -0.1, -1.2), 4, (0.25, 0.1, 0.05, 0.025, -0.025, -0.3)),
    ((3.0, 0, 0, 0, 0, 3.0), 2.0, (1.5, 0, 0, 0, 0, 1.5)),
    ((0, 0, 0, 0, 0, 0), 4, (0, 0, 0, 0, 0, 0)),
])
def test_scale_twist(values, divisor, expected):
    assert scale_twist(values, divisor) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize('values', [
    (math.nan, 0, 0, 0, 0, 0),
    (0, 0, 0, 0, 0, math.inf),
    (0, -math.inf, 0, 0, 0, 0),
])
def test_non_finite_command_is_refused(values):
    with pytest.raises(ValueError, match='non-finite'):
        scale_twist(values)


def test_wrong_length_is_refused():
    with pytest.raises(ValueError, match='expected 6'):
        scale_twist((1.0, 2.0))


@pytest.mark.parametrize('divisor, words', [
    (0, 'divisor = 0: expected a finite number > 0'),
    (-4, 'divisor = -4: expected a finite number > 0'),
    (math.nan, 'divisor = nan: expected a finite number > 0'),
    (math.inf, 'divisor = inf: expected a finite number > 0'),
    ('4', "divisor = '4': expected a finite number > 0"),
    (True, 'divisor = True: expected a finite number > 0'),
])
def test_bad_divisor(divisor, words):
    with pytest.raises(ValueError, match=words):
        check_divisor(divisor)


@pytest.mark.parametrize('pose', [(5.544, 5.544, 0.0), (0.0, 11.08, -3.14), (1, 2, 3)])
def test_pose2d_fields(pose):
    assert pose2d_fields(*pose) == pytest.approx(pose, abs=TOL)


@pytest.mark.parametrize('pose', [(math.nan, 1, 1), (1, math.inf, 1), (1, 1, -math.inf)])
def test_non_finite_pose_is_refused(pose):
    with pytest.raises(ValueError, match='non-finite'):
        pose2d_fields(*pose)
