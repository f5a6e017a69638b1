"""Unit tests for mimic's topic resolution and pose-to-command copy (mimic_relay)."""

import math

import pytest
from turtle_lite.mimic_relay import mimic_topics, pose_to_command


@pytest.mark.parametrize(
    ("namespace", "node_name", "mappings", "expected"),
    [
        ("/", "/turtle_mimic", {}, ("/input/pose", "/output/cmd_vel")),
        # The ROS wiki usage with multisim.launch.
        ("/", "/turtle_mimic",
         {"input": "turtlesim1/turtle1", "output": "turtlesim2/turtle1"},
         ("/turtlesim1/turtle1/pose", "/turtlesim2/turtle1/cmd_vel")),
        # rospy's get_namespace() has a trailing slash; relative names follow the namespace.
        ("/g1/", "/g1/turtle_mimic", {"input": "leader", "output": "/follower"},
         ("/g1/leader/pose", "/follower/cmd_vel")),
        ("/g1", "/g1/turtle_mimic", {}, ("/g1/input/pose", "/g1/output/cmd_vel")),
        # A full-name remap of the topic itself still applies after the namespace remap.
        ("/", "/turtle_mimic", {"input": "t1", "/t1/pose": "/other/pose"},
         ("/other/pose", "/output/cmd_vel")),
        # Private-looking keys such as __name are not remappings.
        ("/", "/m", {"__name": "m", "output": "~out"}, ("/input/pose", "/m/out/cmd_vel")),
    ],
)
def test_mimic_topics(namespace, node_name, mappings, expected):
    assert mimic_topics(namespace, node_name, mappings) == expected


def test_invalid_remapped_namespace_raises():
    with pytest.raises(ValueError):
        mimic_topics("/", "/turtle_mimic", {"input": "my turtle"})


@pytest.mark.parametrize(
    ("linear", "angular", "expected"),
    [
        (0.0, 0.0, (0.0, 0.0)),
        # A reversing leader reports a positive magnitude: the follower goes forward.
        (2.0, 0.0, (2.0, 0.0)),
        (1.5, -0.75, (1.5, -0.75)),
        (0.0, 2.0, (0.0, 2.0)),
    ],
)
def test_pose_to_command_copies(linear, angular, expected):
    # A plain copy: exact up to float rounding (1e-12).
    assert pose_to_command(linear, angular) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize(
    ("linear", "angular", "field"),
    [(math.nan, 0.0, "linear_velocity"), (math.inf, 0.0, "linear_velocity"),
     (0.0, -math.inf, "angular_velocity"), (0.0, math.nan, "angular_velocity")],
)
def test_non_finite_raises(linear, angular, field):
    with pytest.raises(ValueError, match=field):
        pose_to_command(linear, angular)
