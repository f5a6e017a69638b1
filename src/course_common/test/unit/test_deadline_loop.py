"""course_common.deadline_loop: the loop, on a fake clock and sleep."""
import pytest
from course_common.deadline_loop import DeadlineLoop
from course_common.schedule import Deadlines

from course_common import deadline_loop

TOL_S = 1e-9  # sums of a few float periods


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
    monkeypatch.setattr(deadline_loop, 'shutdown_requested', lambda: True)
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
