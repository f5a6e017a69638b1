"""Unit tests of stage_multi.drive: move_robot's command, rate and names as the lesson has them."""
import pytest
from course_common.robot_ids import BAD_ROBOT_ID
from stage_multi.drive import (
    FORWARD_SPEED_MPS,
    RATE_HZ,
    cmd_vel_topic,
    node_name,
)


def test_the_lessons_figures():
    assert (FORWARD_SPEED_MPS, RATE_HZ) == (0.2, 10.0)


@pytest.mark.parametrize('robot_id, node, topic', [
    (0, 'move_robot_0', 'robot_0/cmd_vel'),
    (3, 'move_robot_3', 'robot_3/cmd_vel'),
    (19, 'move_robot_19', 'robot_19/cmd_vel'),
])
def test_names_are_the_lessons_and_relative(robot_id, node, topic):
    assert node_name(robot_id) == node
    assert cmd_vel_topic(robot_id) == topic


@pytest.mark.parametrize('robot_id', [-1, 20, 1.0, '1', None, True])
@pytest.mark.parametrize('name', [node_name, cmd_vel_topic])
def test_bad_ids_raise_with_the_lessons_message(name, robot_id):
    with pytest.raises(ValueError) as err:
        name(robot_id)
    assert str(err.value).startswith(BAD_ROBOT_ID)
