"""Unit tests of turtle_lite.team_frames: pose topic discovery, frame names, pose -> transform."""

import math

import pytest
from turtle_lite.team_frames import (
    POSE_TYPE,
    Transform,
    diff_topics,
    frame_for_pose_topic,
    pose_to_transform,
    pose_topics,
)

TOL = 1e-12  # pure float maths: exact up to rounding


@pytest.mark.parametrize('topic, namespace, frame', [
    ('/turtle1/pose', '/', 'turtle1'),
    ('/robot1/pose', '/', 'robot1'),
    ('/robot_0/pose', '/', 'robot_0'),
    ('/turtlesim1/turtle1/pose', '/', 'turtlesim1/turtle1'),
    ('/turtlesim1/turtle1/pose', '/turtlesim1', 'turtle1'),
    ('/turtlesim1/turtle1/pose', 'turtlesim1/', 'turtle1'),
    ('/turtlesim2/turtle1/pose', '/turtlesim1', None),   # another simulator
    ('/pose', '/', None),                                # no turtle name
    ('/robot1/cmd_vel', '/', None),                      # not a pose
    ('/robot1/pose/extra', '/', None),
    ('/robot1//pose', '/', None),                        # empty name segment
    ('/robot1/posey', '/', None),
])
def test_frame_for_pose_topic(topic, namespace, frame):
    assert frame_for_pose_topic(topic, namespace) == frame


PUBLISHED = [
    ['/rosout', 'rosgraph_msgs/Log'],
    ['/robot1/pose', POSE_TYPE],
    ['/robot2/pose', POSE_TYPE],
    ['/robot1/color_sensor', 'turtlesim/Color'],
    ['/odd/pose', 'geometry_msgs/Pose'],   # a pose topic of another type is not a turtle's
    ['/sim/turtle1/pose', POSE_TYPE],
]


@pytest.mark.parametrize('namespace, only, expected', [
    ('/', (), {'/robot1/pose': 'robot1', '/robot2/pose': 'robot2',
               '/sim/turtle1/pose': 'sim/turtle1'}),
    ('/sim', (), {'/sim/turtle1/pose': 'turtle1'}),
    ('/', ('robot2',), {'/robot2/pose': 'robot2'}),
    ('/', ('nobody',), {}),
    ('/nothing', (), {}),
])
def test_pose_topics(namespace, only, expected):
    assert pose_topics(PUBLISHED, namespace, only) == expected


def test_pose_topics_of_an_empty_graph():
    assert pose_topics([], '/') == {}


@pytest.mark.parametrize('old, new, added, removed', [
    ({}, {'/a/pose': 'a'}, {'/a/pose': 'a'}, []),                       # spawn
    ({'/a/pose': 'a', '/b/pose': 'b'}, {'/a/pose': 'a'}, {}, ['/b/pose']),  # kill
    ({'/a/pose': 'a'}, {'/a/pose': 'a'}, {}, []),                       # nothing new
    ({'/b/pose': 'b', '/a/pose': 'a'}, {}, {}, ['/a/pose', '/b/pose']),  # simulator gone
    ({'/a/pose': 'a'}, {'/a/pose': 'x'}, {'/a/pose': 'x'}, ['/a/pose']),  # renamed frame
])
def test_diff_topics(old, new, added, removed):
    assert diff_topics(old, new) == (added, removed)


@pytest.mark.parametrize('x, y, theta', [
    (5.544445, 5.544445, 0.0), (1.0, 2.0, math.pi / 2), (0.0, 11.088889, -math.pi),
    (3.0, 4.0, 3.14159265), (7.5, 0.25, -1.2),
])
def test_pose_to_transform_is_the_yaw_rotation(x, y, theta):
    t = pose_to_transform(x, y, theta)
    assert isinstance(t, Transform)
    assert (t.x, t.y, t.z) == (x, y, 0.0)
    assert t.qx == 0.0 and t.qy == 0.0
    assert t.qx ** 2 + t.qy ** 2 + t.qz ** 2 + t.qw ** 2 == pytest.approx(1.0, abs=TOL)
    # The yaw back from the quaternion, as tf's euler_from_quaternion computes it.
    yaw = math.atan2(2.0 * (t.qw * t.qz + t.qx * t.qy), 1.0 - 2.0 * (t.qy ** 2 + t.qz ** 2))
    assert math.cos(yaw) == pytest.approx(math.cos(theta), abs=TOL)
    assert math.sin(yaw) == pytest.approx(math.sin(theta), abs=TOL)


@pytest.mark.parametrize('x, y, theta, field', [
    (math.nan, 1.0, 0.0, 'x'), (1.0, math.inf, 0.0, 'y'), (1.0, 1.0, -math.inf, 'theta'),
    ('1', 1.0, 0.0, 'x'), (1.0, None, 0.0, 'y'), (1.0, 1.0, True, 'theta'),
])
def test_pose_to_transform_rejects_bad_numbers(x, y, theta, field):
    with pytest.raises(ValueError, match='pose %s' % field):
        pose_to_transform(x, y, theta)
