"""course_common.rviz.snapshot.RvizOnXvfb: rviz dying of a signal as it starts is started
again once; a second death, or an exit of its own, fails the wait (a stand-in for rviz)."""
import pytest
from course_common.rviz.snapshot import CRASH_RESTARTS, RvizOnXvfb
from course_common.waiting import wait_for

DEADLINE_S = 10.0


def _stand_in(argv):
    """An RvizOnXvfb whose 'rviz' is argv, on no X display (its start is what is tested)."""
    rviz = RvizOnXvfb.__new__(RvizOnXvfb)
    rviz._argv, rviz.display, rviz.restarts = argv, ':0', 0
    rviz._rviz = rviz._start_rviz()
    return rviz


def _dead(rviz):
    wait_for(lambda: not rviz.running(), DEADLINE_S, 'the stand-in to end')


def test_a_death_by_a_signal_is_started_again_once_then_fails():
    rviz = _stand_in(['sh', '-c', 'kill -ABRT $$'])
    for _ in range(CRASH_RESTARTS):
        _dead(rviz)
        assert rviz.alive_and(lambda: 'drawn') is None  # started again: the wait goes on
    assert rviz.restarts == CRASH_RESTARTS
    _dead(rviz)
    with pytest.raises(AssertionError, match='rviz exited'):
        rviz.alive_and(lambda: 'drawn')


def test_an_exit_of_its_own_fails_at_once():
    rviz = _stand_in(['sh', '-c', 'exit 3'])
    _dead(rviz)
    with pytest.raises(AssertionError, match=r'rviz exited \(code 3\)'):
        rviz.alive_and(lambda: 'drawn')
    assert rviz.restarts == 0


def test_a_running_rviz_is_checked():
    rviz = _stand_in(['sleep', '30'])
    try:
        assert rviz.alive_and(lambda: 'drawn') == 'drawn'
    finally:
        rviz._rviz.stop()
