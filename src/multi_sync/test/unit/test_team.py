"""Unit tests for multi_sync.team: argv checks and the monitor's team bookkeeping."""
import pytest
from multi_sync.team import (
    BAD_ROBOT_ID,
    BAD_TEAM_SIZE,
    MISSING_ROBOT_ID,
    MISSING_TEAM_SIZE,
    Outcome,
    TeamBook,
    parse_robot_id,
    parse_team_size,
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


@pytest.mark.parametrize('size', [0, 21, -3, 2.0, '4', None, True])
def test_teambook_rejects_bad_size(size):
    with pytest.raises(ValueError):
        TeamBook(size)


@pytest.mark.parametrize('reports, outcomes', [
    # (robot_id, is_ready, frame_id) in order -> outcome of each, team of 3
    ([(0, True, ''), (1, True, ''), (2, True, '')],
     [Outcome.NEW_READY, Outcome.NEW_READY, Outcome.TEAM_READY]),
    # duplicates are not counted twice
    ([(0, True, ''), (0, True, ''), (1, True, ''), (1, True, ''), (2, True, '')],
     [Outcome.NEW_READY, Outcome.DUPLICATE, Outcome.NEW_READY, Outcome.DUPLICATE,
      Outcome.TEAM_READY]),
    # the monitor's own GO, bad ids and not-ready reports are ignored
    ([(-1, True, 'monitor'), (0, True, ''), (20, True, ''), (-1, True, ''), (1, False, ''),
      (1, True, ''), (5, True, '')],
     [Outcome.MONITOR, Outcome.NEW_READY, Outcome.BAD_ID, Outcome.BAD_ID, Outcome.NOT_READY,
      Outcome.NEW_READY, Outcome.TEAM_READY]),
    # after GO a ready report (new or known robot) is only recorded: GO reaches every
    # subscriber once (multi_sync.go_latch), a report does not send it again
    ([(0, True, ''), (1, True, ''), (2, True, ''), (2, True, ''), (7, True, ''),
      (0, True, 'monitor')],
     [Outcome.NEW_READY, Outcome.NEW_READY, Outcome.TEAM_READY, Outcome.AFTER_GO,
      Outcome.AFTER_GO, Outcome.MONITOR]),
])
def test_teambook_outcomes(reports, outcomes):
    book = TeamBook(3)
    assert [book.report(*r) for r in reports] == outcomes
    assert book.go_given


def test_teambook_go_only_once_and_counts_distinct():
    book = TeamBook(2)
    assert not book.go_given
    book.report(4, True)
    book.report(4, True)
    assert book.ready_count == 1 and not book.go_given
    assert book.report(9, True) is Outcome.TEAM_READY
    assert book.report(11, True) is Outcome.AFTER_GO
    assert book.ready_count == 3


@pytest.mark.parametrize('reports', [
    # (robot_id, sender) after robot 0 completed a team of one, in the racy orders seen:
    [(0, '/move_robot_0')],   # re-announced before reading the GO written to it
    [(0, '/move_robot_0')] * 3,  # not subscribed at a forced GO; subscribed, GO on its way
    [(0, '')],                # sender unknown
    [(7, '/move_robot_7')],   # a robot started after GO: it gets GO as it subscribes
])
def test_teambook_ready_crossing_go_asks_for_no_second_go(reports):
    """The flake "2 != 1 : one GO": before the fix such a report made the monitor send GO again."""
    book = TeamBook(1)
    assert book.report(0, True, '', '/move_robot_0') is Outcome.TEAM_READY
    for robot_id, sender in reports:
        assert book.report(robot_id, True, '', sender) is Outcome.AFTER_GO
    assert book.go_given


def test_teambook_of_one_goes_on_first_ready():
    assert TeamBook(1).report(19, True) is Outcome.TEAM_READY


def test_teambook_full_team_of_twenty():
    book = TeamBook(20)
    outcomes = [book.report(i, True) for i in reversed(range(20))]
    assert outcomes[:-1] == [Outcome.NEW_READY] * 19
    assert outcomes[-1] is Outcome.TEAM_READY


@pytest.mark.parametrize('reports, listeners, expected', [
    # (robot_id, sender) ready reports; the nodes subscribed to the GO; ids not listening
    ([(0, '/move_robot_0'), (1, '/move_robot_1')], {'/move_robot_0', '/move_robot_1'}, []),
    ([(0, '/move_robot_0'), (1, '/move_robot_1')], {'/move_robot_1', '/rostopic'}, [0]),
    ([(0, '/a'), (1, '/b'), (2, '/c')], set(), [0, 1, 2]),
    ([(0, ''), (1, '/b')], {'/b'}, []),               # unknown sender: cannot check it
    ([(0, '/old'), (0, '/new')], {'/new'}, []),        # a restarted robot: latest sender
    ([(25, '/bad'), (0, '/a')], {'/a'}, []),           # bad ids are never recorded
])
def test_teambook_unconnected(reports, listeners, expected):
    book = TeamBook(20)
    for robot_id, sender in reports:
        book.report(robot_id, True, '', sender)
    assert book.unconnected(listeners) == expected
