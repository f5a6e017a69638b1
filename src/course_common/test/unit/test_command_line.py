"""Unit tests of course_common.command_line: the parsed arguments, or the error and exit 1."""
import pytest
import rospy
from course_common.command_line import parse_argv_or_exit


class UsageError(ValueError):
    """A parser's own ValueError subclass (my_turtle has one)."""


def _count(args):
    if len(args) != 1:
        raise UsageError('expected one number, got %d arguments' % len(args))
    return int(args[0])  # int('x') raises ValueError with Python's own message


@pytest.fixture
def errors(monkeypatch):
    logged = []
    monkeypatch.setattr(rospy, 'logerr', logged.append)
    return logged


@pytest.mark.parametrize('argv, expected', [
    (['prog', '3'], 3),
    (['prog', '__name:=robot', '4', 'cmd_vel:=/robot/cmd_vel'], 4),  # ROS remaps removed
    (['prog', '__log:=/tmp/x.log', '-5'], -5),
])
def test_returns_the_parse_of_the_arguments(argv, expected, errors):
    assert parse_argv_or_exit(_count, argv) == expected
    assert errors == []


@pytest.mark.parametrize('argv, label, message', [
    (['prog'], None, 'expected one number, got 0 arguments'),
    (['prog', '1', '2'], 'monitor', 'monitor: expected one number, got 2 arguments'),
    (['prog', 'x'], 'move_turtle', "move_turtle: invalid literal for int() with base 10: 'x'"),
    (['prog', 'a:=b'], None, 'expected one number, got 0 arguments'),
])
def test_a_bad_command_line_logs_the_error_and_exits_1(argv, label, message, errors):
    with pytest.raises(SystemExit) as exited:
        parse_argv_or_exit(_count, argv, label)
    assert exited.value.code == 1
    assert errors == [message]


def test_reads_sys_argv_by_default(monkeypatch, errors):
    monkeypatch.setattr('sys.argv', ['prog', '7', '__ns:=/team'])
    assert parse_argv_or_exit(_count) == 7


def test_other_errors_are_not_usage_errors(errors):
    def broken(_args):
        raise KeyError('a bug, not a bad command line')

    with pytest.raises(KeyError):
        parse_argv_or_exit(broken, ['prog'])
    assert errors == []
