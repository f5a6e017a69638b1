"""Sim time in whole ns, the wall-clock schedule and the shared watchdog."""
import math

import pytest
from stage_lite.node.pacing import (
    FLAT_OUT,
    PAUSED_POLL_S,
    Pacer,
    SimClock,
    Watchdog,
    check_speedup,
    faster,
    slower,
    world_speedup,
)

TOL = 1e-9  # s: schedules are sums of a few floats


def test_sim_clock_counts_whole_intervals_and_never_starts_at_zero_after_a_step():
    clock = SimClock(0.1)
    assert clock.now_ns == 0
    assert [clock.tick() for _ in range(3)] == [100_000_000, 200_000_000, 300_000_000]
    for _ in range(7):
        clock.tick()
    assert clock.stamp() == (1, 0)
    assert clock.now_s == pytest.approx(1.0, abs=TOL)


@pytest.mark.parametrize('interval', [0.0, -0.1, math.nan, math.inf])
def test_sim_clock_refuses_bad_intervals(interval):
    with pytest.raises(ValueError):
        SimClock(interval)


@pytest.mark.parametrize('value, expected', [(1, 1.0), (2.5, 2.5), (-1, FLAT_OUT), (0.01, 0.01)])
def test_speedups(value, expected):
    assert check_speedup(value) == expected


@pytest.mark.parametrize('value', [0, -0.5, -2, math.nan, math.inf, True, '2', None])
def test_bad_speedups(value):
    with pytest.raises(ValueError):
        check_speedup(value)


@pytest.mark.parametrize('speedup, period', [(1.0, 0.1), (10.0, 0.01), (0.5, 0.2)])
def test_pacer_spaces_steps_by_interval_over_speedup(speedup, period):
    pacer = Pacer(0.1, speedup, now_s=100.0)
    assert pacer.delay(100.0) == 0.0
    pacer.done(100.0)
    assert pacer.delay(100.0) == pytest.approx(period, abs=TOL)
    pacer.done(100.0 + period)
    assert pacer.delay(100.0 + period) == pytest.approx(period, abs=TOL)


def test_pacer_flat_out_never_waits():
    pacer = Pacer(0.1, FLAT_OUT, now_s=5.0)
    for now in (5.0, 5.0, 5.001):
        assert pacer.delay(now) == 0.0
        pacer.done(now)


def test_pacer_catches_up_a_little_then_restarts_its_schedule():
    pacer = Pacer(0.1, 1.0, now_s=0.0)
    pacer.done(0.25)  # a little late: the next step is due at 0.1 (catch up)
    assert pacer.delay(0.25) == 0.0
    pacer.done(10.0)  # far behind: start again from now
    assert pacer.delay(10.0) == pytest.approx(0.0, abs=TOL)


@pytest.mark.parametrize('speedup, up, down', [(1.0, 1.2, 0.8), (FLAT_OUT, FLAT_OUT, 100.0)])
def test_run_menu_speeds_are_stages(speedup, up, down):
    assert faster(speedup) == pytest.approx(up, abs=TOL)
    assert slower(speedup) == pytest.approx(down, abs=TOL)


def test_pacer_changes_speed_from_now():
    pacer = Pacer(0.1, 1.0, now_s=0.0)
    pacer.done(0.0)
    pacer.set_speedup(10.0, now_s=0.05)          # due at once, then every 10 ms
    assert pacer.delay(0.05) == 0.0
    pacer.done(0.05)
    assert pacer.delay(0.05) == pytest.approx(0.01, abs=TOL)
    pacer.set_speedup(FLAT_OUT, now_s=0.06)
    pacer.done(0.06)
    assert pacer.delay(0.06) == 0.0
    with pytest.raises(ValueError):
        pacer.set_speedup(0.0, now_s=0.07)


def test_pacer_restarts_from_now():
    pacer = Pacer(0.1, 1.0, now_s=0.0)           # made at start-up, the loop starts later
    pacer.restart(7.0)
    assert pacer.delay(6.95) == pytest.approx(0.05, abs=TOL)
    assert pacer.delay(7.0) == 0.0
    pacer.done(7.0)
    assert pacer.delay(7.0) == pytest.approx(0.1, abs=TOL)


def test_paused_pacer_steps_only_when_asked_and_resumes_without_a_burst():
    pacer = Pacer(0.1, 1.0, now_s=0.0, paused=True)
    assert pacer.delay(50.0) == PAUSED_POLL_S
    pacer.step_once()
    pacer.step_once()
    for _ in range(2):
        assert pacer.delay(50.0) == 0.0
        pacer.done(50.0)
    assert pacer.delay(50.0) == PAUSED_POLL_S     # two steps asked, two made
    pacer.set_paused(False, now_s=60.0)
    assert pacer.delay(60.0) == 0.0
    pacer.done(60.0)
    assert pacer.delay(60.0) == pytest.approx(0.1, abs=TOL)   # one step now, not 100
    pacer.step_once()                                        # running: nothing to ask
    pacer.done(60.1)
    assert pacer.delay(60.1) == pytest.approx(0.1, abs=TOL)


@pytest.mark.parametrize('timeout, last, now, expired', [
    (0.2, 0.1, 0.2, False),
    (0.2, 0.1, 0.3, True),
    (0.2, 0.5, 0.7, True),      # 0.7 - 0.5 is 0.19999.. in floats; whole ns make it 0.2
    (0.2, 0.5, 0.6, False),
    (0.0, 0.0, 100.0, False),   # disabled
    (-1.0, 0.0, 100.0, False),
])
def test_watchdog(timeout, last, now, expired):
    dog = Watchdog(timeout)
    dog.command(round(last * 1e9))
    assert dog.expired(round(now * 1e9)) is expired


@pytest.mark.parametrize('value, expected', [
    (1.0, 1.0), (2.5, 2.5), (0.0, FLAT_OUT), (-1.0, FLAT_OUT), (-3.0, FLAT_OUT),
    (math.nan, FLAT_OUT), (math.inf, FLAT_OUT)])
def test_a_worlds_speedup_as_stages_window_reads_it(value, expected):
    assert world_speedup(value) == expected
