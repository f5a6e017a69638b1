"""Unit tests of course_common.pose_topics: which topics are robots' poses, and whose."""
import pytest
from course_common.pose_topics import POSE_TYPE, pose_topics, robot_of_pose_topic


@pytest.mark.parametrize('topic, namespace, robot', [
    ('/turtle1/pose', '/', 'turtle1'),
    ('/robot1/pose', '/', 'robot1'),
    ('/robot_0/pose', '/', 'robot_0'),
    ('robot2/pose', '/', 'robot2'),                      # a bag's name without the '/'
    ('/team/robot3/pose', '/', 'team/robot3'),
    ('/turtlesim1/turtle1/pose', '/', 'turtlesim1/turtle1'),  # two simulators stay apart
    ('/turtlesim1/turtle1/pose', '/turtlesim1', 'turtle1'),
    ('/turtlesim1/turtle1/pose', 'turtlesim1/', 'turtle1'),
    ('/turtlesim2/turtle1/pose', '/turtlesim1', None),   # another simulator
    ('/pose', '/', None),                                # no robot name
    ('/robot1/cmd_vel', '/', None),                      # not a pose
    ('/robot1/pose/extra', '/', None),
    ('/robot1/pose_stamped', '/', None),
    ('/robot1/posey', '/', None),
    ('/robot1//pose', '/', None),                        # empty name segment
    ('', '/', None),
])
def test_robot_of_pose_topic(topic, namespace, robot):
    assert robot_of_pose_topic(topic, namespace) == robot


@pytest.mark.parametrize('topic, namespace', [(None, '/'), (42, '/'), ('/a/pose', None)])
def test_robot_of_pose_topic_refuses_non_strings(topic, namespace):
    with pytest.raises(ValueError, match='expected a string'):
        robot_of_pose_topic(topic, namespace)


PUBLISHED = [                     # as the master's getPublishedTopics gives them
    ['/rosout', 'rosgraph_msgs/Log'],
    ['/robot1/pose', POSE_TYPE],
    ['/robot2/pose', POSE_TYPE],
    ['/robot1/color_sensor', 'turtlesim/Color'],
    ['/odd/pose', 'geometry_msgs/Pose'],   # a pose topic of another type is not a robot's
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
def test_pose_topics_of_the_master(namespace, only, expected):
    assert pose_topics(PUBLISHED, namespace, only) == expected


@pytest.mark.parametrize('table, expected', [   # a bag's {topic: type}
    ({'/robot1/pose': POSE_TYPE, '/robot2/pose': POSE_TYPE,
      '/robot1/cmd_vel': 'geometry_msgs/Twist', '/rosout': 'rosgraph_msgs/Log'},
     {'/robot1/pose': 'robot1', '/robot2/pose': 'robot2'}),
    ({'/robot1/pose': 'geometry_msgs/Pose2D', '/robot2/pose': POSE_TYPE},
     {'/robot2/pose': 'robot2'}),
    ({'/robot1/cmd_vel': 'geometry_msgs/Twist', '/pose': POSE_TYPE}, {}),
    ({}, {}),
])
def test_pose_topics_of_a_bag(table, expected):
    assert pose_topics(table) == expected


def test_pose_topics_of_an_empty_graph():
    assert pose_topics([], '/') == {}
