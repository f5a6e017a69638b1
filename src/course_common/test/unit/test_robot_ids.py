"""Unit tests for course_common.robot_ids: the lessons' argv checks and their messages."""
import pytest
from course_common.robot_ids import (
    BAD_ROBOT_ID,
    BAD_TEAM_SIZE,
    MAX_ROBOTS,
    MISSING_ROBOT_ID,
    MISSING_TEAM_SIZE,
    parse_plain_int,
    parse_robot_id,
    parse_team_size,
    valid_robot_id,
)


@pytest.mark.parametrize('args, expected', [
    (['1'], 1), (['4'], 4), (['20'], 20), ([' 7 '], 7), (['+3'], 3), (['4', 'extra'], 4),
])
def test_team_size_accepted(args, expected):
    assert parse_team_size(args) == expected


@pytest.mark.parametrize('args, message', [
    ([], MISSING_TEAM_SIZE),
    (['0'], BAD_TEAM_SIZE), (['21'], BAD_TEAM_SIZE), (['-1'], BAD_TEAM_SIZE),
    (['abc'], BAD_TEAM_SIZE), (['4abc'], BAD_TEAM_SIZE), (['4.0'], BAD_TEAM_SIZE),
    ([''], BAD_TEAM_SIZE), (['nan'], BAD_TEAM_SIZE), (['\u0664'], BAD_TEAM_SIZE),
])
def test_team_size_rejected_with_lesson_message(args, message):
    with pytest.raises(ValueError) as err:
        parse_team_size(args)
    assert str(err.value) == message


def test_lesson_messages_verbatim():
    assert MISSING_TEAM_SIZE == 'You must specify team size.'
    assert BAD_TEAM_SIZE == 'The team size must be an integer number between 1 and 20'
    assert MISSING_ROBOT_ID == 'You must specify robot id.'
    assert BAD_ROBOT_ID == "The robot's ID must be an integer number between 0 and 19"


@pytest.mark.parametrize('args, expected', [(['0'], 0), (['19'], 19), (['3', 'x'], 3)])
def test_robot_id_accepted(args, expected):
    assert parse_robot_id(args) == expected


@pytest.mark.parametrize('args, message', [
    ([], MISSING_ROBOT_ID),
    (['20'], BAD_ROBOT_ID),  # the lesson's off-by-one let 20 through
    (['-1'], BAD_ROBOT_ID), (['x'], BAD_ROBOT_ID), (['1.5'], BAD_ROBOT_ID), ([''], BAD_ROBOT_ID),
])
def test_robot_id_rejected_with_lesson_message(args, message):
    with pytest.raises(ValueError) as err:
        parse_robot_id(args)
    assert str(err.value) == message


@pytest.mark.parametrize('text, expected', [
    ('7', 7), (' -3 ', -3), ('+0', 0), ('4abc', None), ('4.0', None), ('', None), ('-', None),
    ('\u0664', None),  # an Arabic-Indic digit: isdigit() says yes, the lesson's atoi no
])
def test_parse_plain_int(text, expected):
    assert parse_plain_int(text) == expected


@pytest.mark.parametrize('robot_id, expected', [
    (0, True), (MAX_ROBOTS - 1, True), (MAX_ROBOTS, False), (-1, False), (1.0, False),
    ('1', False), (None, False), (True, False), (False, False),
])
def test_valid_robot_id(robot_id, expected):
    assert valid_robot_id(robot_id) is expected
