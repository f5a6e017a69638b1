"""Unit tests of course_common.planar: the lessons' pose and command, and the pose check."""
import dataclasses
import math

import pytest
from course_common.planar import STOP, Command, Pose, check_pose, is_finite_pose


def test_stop_is_zero_and_values_are_frozen():
    assert (STOP.linear_mps, STOP.angular_radps) == (0.0, 0.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        Pose(1.0, 2.0, 0.0).x = 3.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        Command(1.0, 0.5).linear_mps = 0.0


def test_equal_by_value():
    assert Pose(1.0, 2.0, 0.5) == Pose(1.0, 2.0, 0.5)
    assert Command(1.0, -0.5) != Command(1.0, 0.5)


@pytest.mark.parametrize('pose, finite', [
    (Pose(0.0, 0.0, 0.0), True),
    (Pose(5.5, -1, 3.14), True),
    (Pose(math.nan, 1.0, 0.0), False),
    (Pose(1.0, math.inf, 0.0), False),
    (Pose(1.0, 1.0, -math.inf), False),
    (Pose(1.0, 1.0, True), False),
    (Pose('1', 1.0, 0.0), False),
])
def test_is_finite_pose(pose, finite):
    assert is_finite_pose(pose) is finite


def test_check_pose_returns_a_finite_pose():
    pose = Pose(1.0, 2.0, 3.0)
    assert check_pose(pose) is pose


@pytest.mark.parametrize('what, pose, text', [
    ('pose', Pose(math.nan, 1.0, 0.0), 'pose (x=nan, y=1.0, theta=0.0) has a non-finite field'),
    ('goal', Pose(1.0, 2.0, math.inf), 'goal (x=1.0, y=2.0, theta=inf) has a non-finite field'),
])
def test_check_pose_names_what_and_the_fields(what, pose, text):
    with pytest.raises(ValueError) as err:
        check_pose(pose, what)
    assert str(err.value).startswith(text)
