"""course_common.deadline_loop: the schedule (pure) and the loop, on a fake clock and sleep."""
import pytest
import rospy
from course_common.deadline_loop import DeadlineLoop, Deadlines

from course_common import deadline_loop

TOL_S = 1e-9  # sums of a few float periods


@pytest.mark.parametrize('period_s, first_s, ends, nexts', [
    # on time: each deadline one period after the last, never after the call's end
    (0.1, 0.0, [0.0, 0.1, 0.2], [0.1, 0.2, 0.3]),
    # a little late: the next deadline stays on the grid (catch up, no drift)
    (0.1, 0.0, [0.25], [0.1]),
    # more than max_lag (4) periods behind: the schedule restarts from then
    (0.1, 0.0, [0.55], [0.55]),
    # just inside the lag: still on the grid
    (0.1, 0.0, [0.45], [0.1]),
    # no pacing: due again as soon as the call ended
    (0.0, 5.0, [5.0, 5.3, 5.31], [5.0, 5.3, 5.31]),
])
def test_deadlines(period_s, first_s, ends, nexts):
    deadlines = Deadlines(period_s, first_s, max_lag_periods=4)
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


class FakeTime:
    """A monotonic clock that only sleeping moves on."""

    def __init__(self):
        self.now = 10.0
        self.sleeps = []

    def clock(self):
        return self.now

    def sleep(self, delay):
        self.sleeps.append(delay)
        self.now += delay


def _loop(call, fake, period_s=0.1, first_offset_s=0.1):
    return DeadlineLoop(call, lambda: Deadlines(period_s, fake.clock() + first_offset_s, 4),
                        'test_loop', 'test call', clock=fake.clock, sleep=fake.sleep)


def test_calls_come_on_the_deadlines_until_the_call_says_stop():
    fake = FakeTime()
    times = []

    def call():
        times.append(fake.now)
        return len(times) < 3
    _loop(call, fake).run()
    assert times == pytest.approx([10.1, 10.2, 10.3], abs=TOL_S)


def test_stop_ends_the_loop_before_the_next_call():
    fake = FakeTime()
    calls = []

    def call():
        calls.append(fake.now)
        loop.stop()
    loop = _loop(call, fake)
    loop.run()
    assert len(calls) == 1


def test_a_failing_call_is_logged_and_the_loop_goes_on(monkeypatch):
    fake = FakeTime()
    logged = []
    monkeypatch.setattr(deadline_loop.rospy, 'logerr_throttle',
                        lambda period, text: logged.append(text))
    calls = []

    def call():
        calls.append(fake.now)
        if len(calls) == 1:
            raise RuntimeError('boom')
        return False
    _loop(call, fake).run()
    assert len(calls) == 2
    assert logged == ["test call failed: RuntimeError('boom')"]


def test_a_call_failing_after_stop_ends_the_loop_without_a_log(monkeypatch):
    fake = FakeTime()
    logged = []
    monkeypatch.setattr(deadline_loop.rospy, 'logerr_throttle',
                        lambda period, text: logged.append(text))

    def call():
        loop.stop()
        raise RuntimeError('publisher closed')
    loop = _loop(call, fake)
    loop.run()
    assert logged == []


@pytest.mark.parametrize('stop_at_shutdown, calls_made', [(True, 0), (False, 1)])
def test_ros_shutdown_ends_the_loop_only_when_asked(monkeypatch, stop_at_shutdown, calls_made):
    fake = FakeTime()
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: True)
    calls = []
    DeadlineLoop(lambda: calls.append(1) or False,
                 lambda: Deadlines(0.1, fake.clock(), 4), 'test_loop', 'test call',
                 stop_at_shutdown=stop_at_shutdown, clock=fake.clock, sleep=fake.sleep).run()
    assert len(calls) == calls_made


def test_the_thread_starts_and_joins():
    fake = FakeTime()
    loop = _loop(lambda: False, fake, first_offset_s=0.0)
    loop.join(0.1)  # before start: returns at once
    loop.start()
    loop.join(5.0)
    assert not loop._thread.is_alive()
