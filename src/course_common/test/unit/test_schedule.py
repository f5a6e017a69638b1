"""course_common.schedule: a loop's deadlines and the lag rule, the throttle (pure)."""
import pytest
from course_common.schedule import MAX_LAG_PERIODS, Deadlines, Throttle

TOL_S = 1e-9  # sums of a few float periods


def test_one_lag_rule():
    assert MAX_LAG_PERIODS == 4  # the cases below are written for it


@pytest.mark.parametrize('period_s, first_s, ends, nexts', [
    # on time: each deadline one period after the last, never after the call's end
    (0.1, 0.0, [0.0, 0.1, 0.2], [0.1, 0.2, 0.3]),
    # a little late: the next deadline stays on the grid (catch up, no drift)
    (0.1, 0.0, [0.25], [0.1]),
    # more than MAX_LAG_PERIODS (4) periods behind: the schedule restarts from then
    (0.1, 0.0, [0.55], [0.55]),
    # just inside the lag: still on the grid
    (0.1, 0.0, [0.45], [0.1]),
    # no pacing: due again as soon as the call ended
    (0.0, 5.0, [5.0, 5.3, 5.31], [5.0, 5.3, 5.31]),
])
def test_deadlines(period_s, first_s, ends, nexts):
    deadlines = Deadlines(period_s, first_s)
    for end, expected in zip(ends, nexts, strict=True):
        deadlines.done(end)
        assert deadlines.next_s == pytest.approx(expected, abs=TOL_S)


@pytest.mark.parametrize('next_s, now_s, delay_s', [
    (1.0, 0.75, 0.25),
    (1.0, 1.0, 0.0),
    (1.0, 3.0, 0.0),  # overdue: due now, never a negative delay
])
def test_delay(next_s, now_s, delay_s):
    assert Deadlines(0.1, next_s, 4).delay(now_s) == pytest.approx(delay_s, abs=TOL_S)


@pytest.mark.parametrize('period_s, lag', [
    (-0.1, 4), (float('nan'), 4), (float('inf'), 4), (0.1, -1),
])
def test_bad_schedules_are_refused(period_s, lag):
    with pytest.raises(ValueError):
        Deadlines(period_s, 0.0, lag)


def test_throttle_lets_one_through_per_period():
    throttle = Throttle(1.0)
    assert [throttle.ready(t) for t in (0.0, 0.5, 0.99, 1.0, 1.5, 2.5)] == \
        [True, False, False, True, False, True]
