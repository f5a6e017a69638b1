"""Unit tests of convoy.metrics: gap series, catch-up time, summary statistics, percentiles."""
import math

import pytest
from convoy.metrics import (
    catch_up_time,
    delays_since_newest,
    follower_stats,
    gap_series,
    percentile,
)

TOL = 1e-9  # absolute tolerance: closed-form arithmetic only


def _line(t0, t1, dt, x_of_t, y=0.0):
    n = round((t1 - t0) / dt)
    return [(t0 + i * dt, x_of_t(t0 + i * dt), y) for i in range(n + 1)]


def test_gap_uses_newest_leader_sample_and_skips_early_followers():
    leader = [(1.0, 10.0, 0.0), (2.0, 20.0, 0.0)]
    follower = [(0.5, 0.0, 0.0), (1.0, 0.0, 0.0), (1.5, 0.0, 0.0), (2.5, 0.0, 0.0)]
    assert gap_series(leader, follower) == [(1.0, 10.0), (1.5, 10.0), (2.5, 20.0)]


@pytest.mark.parametrize('leader, follower', [
    ([], [(0.0, 0.0, 0.0)]),
    ([(0.0, 0.0, 0.0)], []),
    ([(1.0, 0.0, 0.0), (0.5, 0.0, 0.0)], [(1.0, 0.0, 0.0)]),   # time goes backwards
    ([(0.0, math.nan, 0.0)], [(1.0, 0.0, 0.0)]),
])
def test_gap_series_rejects_bad_samples(leader, follower):
    with pytest.raises(ValueError):
        gap_series(leader, follower)


def test_catch_up_needs_leaving_the_start():
    # Leader and follower spawn on one spot (gap 0): that is not "caught up". The leader
    # drives off at 1 m/s, the follower starts 2 s later at 2 m/s and closes in.
    dt = 0.1
    leader = _line(0.0, 10.0, dt, lambda t: t)
    follower = _line(0.0, 10.0, dt, lambda t: max(0.0, 2.0 * (t - 2.0)))
    gaps = gap_series(leader, follower)
    t = catch_up_time(gaps, follower, threshold_m=2.0)
    # follower leaves 1 m from start at t = 2.5 (gap 1.5 <= 2): caught up then.
    assert t == pytest.approx(2.6, abs=dt + TOL)
    assert catch_up_time(gaps, follower[:20], threshold_m=2.0) is None


def test_follower_stats():
    dt = 0.5
    leader = _line(0.0, 10.0, dt, lambda t: 5.0 + t)
    follower = _line(0.0, 10.0, dt, lambda t: t * 1.5 if t < 10.0 else 15.0)
    stats = follower_stats(leader, follower, threshold_m=2.0, t_origin_s=0.0)
    gaps = [5.0 + t - 1.5 * t for t in (i * dt for i in range(21))]
    gaps[-1] = 0.0
    assert stats.mean_gap_m == pytest.approx(sum(gaps) / len(gaps), abs=TOL)
    assert stats.max_gap_m == pytest.approx(5.0, abs=TOL)
    assert stats.within_fraction == pytest.approx(sum(g <= 2.0 for g in gaps) / 21, abs=TOL)
    assert stats.catch_up_s == pytest.approx(6.0, abs=TOL)
    assert stats.settled_max_gap_m == pytest.approx(2.0, abs=TOL)


@pytest.mark.parametrize('threshold', [0.0, -1.0, math.inf, math.nan])
def test_follower_stats_rejects_bad_threshold(threshold):
    with pytest.raises(ValueError):
        follower_stats([(0.0, 0.0, 0.0)], [(0.0, 1.0, 0.0)], threshold)


@pytest.mark.parametrize('values, fraction, expected', [
    ([3.0, 1.0, 2.0], 0.5, 2.0),
    ([3.0, 1.0, 2.0], 0.0, 1.0),
    ([3.0, 1.0, 2.0], 1.0, 3.0),
    (list(range(1, 101)), 0.99, 99),
    ([7.0], 0.99, 7.0),
])
def test_percentile(values, fraction, expected):
    assert percentile(values, fraction) == pytest.approx(expected, abs=TOL)


@pytest.mark.parametrize('values, fraction', [([], 0.5), ([1.0], 1.5), ([1.0], -0.1)])
def test_percentile_rejects_bad_input(values, fraction):
    with pytest.raises(ValueError):
        percentile(values, fraction)


@pytest.mark.parametrize('causes, effects, delays', [
    ([1.0, 2.0, 3.0], [1.5, 2.0, 3.25], [0.5, 0.0, 0.25]),
    ([1.0, 2.0], [0.5, 1.0, 5.0], [0.0, 3.0]),  # the effect before any cause is skipped
    ([1.0, 2.0], [1.1, 1.2], [pytest.approx(0.1), pytest.approx(0.2)]),  # one cause, two effects
    ([], [1.0], []),
    ([1.0], [], []),
])
def test_delays_since_newest(causes, effects, delays):
    assert delays_since_newest(causes, effects) == delays


@pytest.mark.parametrize('causes, effects', [
    ([2.0, 1.0], [3.0]),
    ([1.0], [3.0, 2.0]),
    ([math.nan], [1.0]),
    ([1.0], [math.inf]),
])
def test_delays_since_newest_rejects(causes, effects):
    with pytest.raises(ValueError):
        delays_since_newest(causes, effects)
