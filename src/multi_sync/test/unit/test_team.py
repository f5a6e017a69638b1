"""Unit tests for multi_sync.team: the monitor's team bookkeeping."""
import pytest
from multi_sync.team import Outcome, TeamBook


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
