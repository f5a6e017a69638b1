"""Unit tests of my_turtle.robot_name: move_turtle's argv and topics."""
import pytest
from my_turtle.robot_name import DEFAULT_ROBOT, UsageError, robot_from_args, robot_topics


@pytest.mark.parametrize('args, robot', [
    ([], 'turtle1'),
    (['turtle2'], 'turtle2'),
    (['robot_1'], 'robot_1'),
    (['/pioneer'], '/pioneer'),
    (['team/turtle3'], 'team/turtle3'),
])
def test_valid_args(args, robot):
    assert robot_from_args(args) == robot


def test_default_is_the_slides_turtle1():
    assert DEFAULT_ROBOT == 'turtle1'


@pytest.mark.parametrize('args, words', [
    (['turtle2', 'turtle3'], 'at most one robot name, got 2'),
    ([''], 'empty'),
    (['my turtle'], 'not a valid ROS name'),
    (['2turtle'], 'not a valid ROS name'),
    (['turtle-2'], 'not a valid ROS name'),
    (['~private'], 'private'),
    (['turtle2/'], 'ends with'),
])
def test_bad_args_name_the_problem_and_usage(args, words):
    with pytest.raises(UsageError) as err:
        robot_from_args(args)
    assert words in str(err.value)
    assert 'usage: rosrun my_turtle move_turtle' in str(err.value)


@pytest.mark.parametrize('robot, topics', [
    ('turtle1', ('turtle1/cmd_vel', 'turtle1/pose')),
    ('turtle2', ('turtle2/cmd_vel', 'turtle2/pose')),
    ('/pioneer', ('/pioneer/cmd_vel', '/pioneer/pose')),
])
def test_robot_topics(robot, topics):
    assert robot_topics(robot) == topics
