"""Convoy run statistics from recorded poses (gap to the leader, catch-up time); pure maths.

Samples are (t_s, x_m, y_m) tuples in time order, t in seconds from any common origin.
"""
import math
from bisect import bisect_right
from dataclasses import dataclass

from course_common.finite import check_finite, is_finite_number

# A follower has "left the corner" once it is this far from where it spawned: before that its
# gap to a leader spawned on the same spot is small without meaning anything.
LEFT_START_M = 1.0


def _check_samples(name, samples):
    if not samples:
        raise ValueError('%s: no samples' % name)
    times = [s[0] for s in samples]
    if any(b < a for a, b in zip(times, times[1:], strict=False)):
        raise ValueError('%s: sample times must not decrease' % name)
    if not all(is_finite_number(v) for s in samples for v in s):
        raise ValueError('%s: samples must be finite' % name)


def gap_series(leader, follower):
    """Distance from the follower to its leader at each follower sample.

    Uses the newest leader sample at or before each follower sample; follower samples older than
    the first leader sample are skipped. Returns a list of (t_s, gap_m). Raises ValueError.
    """
    _check_samples('leader', leader)
    _check_samples('follower', follower)
    leader_times = [s[0] for s in leader]
    series = []
    for t, x, y in follower:
        k = bisect_right(leader_times, t) - 1
        if k >= 0:
            series.append((t, math.hypot(leader[k][1] - x, leader[k][2] - y)))
    return series


@dataclass(frozen=True)
class FollowerStats:
    """Summary of one follower's gap to its leader (metres, seconds)."""

    mean_gap_m: float
    max_gap_m: float
    within_fraction: float  # of samples with gap <= threshold_m
    threshold_m: float
    catch_up_s: float | None  # None if it never caught up
    settled_max_gap_m: float | None  # max gap after catching up; None if it never caught up


def catch_up_time(gaps, follower, threshold_m, left_start_m=LEFT_START_M):
    """First time the follower, away from its start, is within threshold_m of its leader.

    `gaps` is gap_series(leader, follower); returns None if that never happens.
    """
    x0, y0 = follower[0][1], follower[0][2]
    left_at = next((t for t, x, y in follower if math.hypot(x - x0, y - y0) > left_start_m), None)
    if left_at is None:
        return None
    return next((t for t, gap in gaps if t >= left_at and gap <= threshold_m), None)


def follower_stats(leader, follower, threshold_m, t_origin_s=None):
    """FollowerStats for one leader/follower pair; times relative to t_origin_s (default: the
    follower's first sample). Raises ValueError on empty or bad samples or a bad threshold."""
    check_finite('threshold_m', threshold_m, low=0.0, low_open=True)
    gaps = gap_series(leader, follower)
    if not gaps:
        raise ValueError('no follower sample after the first leader sample')
    origin = follower[0][0] if t_origin_s is None else t_origin_s
    values = [g for _, g in gaps]
    caught = catch_up_time(gaps, follower, threshold_m)
    settled = [g for t, g in gaps if caught is not None and t >= caught]
    return FollowerStats(
        mean_gap_m=sum(values) / len(values),
        max_gap_m=max(values),
        within_fraction=sum(1 for g in values if g <= threshold_m) / len(values),
        threshold_m=threshold_m,
        catch_up_s=None if caught is None else caught - origin,
        settled_max_gap_m=max(settled) if settled else None)


def delays_since_newest(causes_s, effects_s):
    """For each effect time, the time since the newest cause at or before it (seconds).

    E.g. a follower's pose receipt times and its command receipt times: each command answers
    the newest pose. Effects before the first cause are skipped; both lists in time order.
    Raises ValueError if a list's times decrease or are not finite.
    """
    for name, times in (('causes', causes_s), ('effects', effects_s)):
        if not all(is_finite_number(t) for t in times):
            raise ValueError('%s: times must be finite' % name)
        if any(b < a for a, b in zip(times, times[1:], strict=False)):
            raise ValueError('%s: times must not decrease' % name)
    delays = []
    for t in effects_s:
        k = bisect_right(causes_s, t) - 1
        if k >= 0:
            delays.append(t - causes_s[k])
    return delays


def percentile(values, fraction):
    """The `fraction` (0..1) percentile of values, nearest-rank. Raises ValueError if empty."""
    if not values:
        raise ValueError('percentile of no values')
    if not 0.0 <= fraction <= 1.0:
        raise ValueError('fraction must be in [0, 1], got %r' % (fraction,))
    ordered = sorted(values)
    rank = max(1, math.ceil(fraction * len(ordered)))
    return ordered[rank - 1]
