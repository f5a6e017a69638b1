"""Unit tests of convoy.report: pairing, the report window, the table."""
import math

import pytest
from convoy.report import (
    chain_pairs,
    natural_key,
    parse_pairs,
    report_pairs,
    table_lines,
)

TOL = 1e-9  # absolute tolerance: closed-form arithmetic only


@pytest.mark.parametrize('names, ordered', [
    (['robot10', 'robot2', 'robot1'], ['robot1', 'robot2', 'robot10']),
    (['b', 'a10', 'a9'], ['a9', 'a10', 'b']),
    (['turtle2', 'robot1'], ['robot1', 'turtle2']),
    (['r1x2', 'r1x10', 'r1'], ['r1', 'r1x2', 'r1x10']),
])
def test_natural_key(names, ordered):
    assert sorted(names, key=natural_key) == ordered


@pytest.mark.parametrize('robots, pairs', [
    (['robot1'], []),
    (['robot2', 'robot1'], [('robot2', 'robot1')]),
    (['robot3', 'robot10', 'robot1', 'robot2'],
     [('robot2', 'robot1'), ('robot3', 'robot2'), ('robot10', 'robot3')]),
    ({'robot1': [], 'robot2': []}, [('robot2', 'robot1')]),
])
def test_chain_pairs(robots, pairs):
    assert chain_pairs(robots) == pairs


@pytest.mark.parametrize('text, pairs', [
    ('robot2:robot1', [('robot2', 'robot1')]),
    ('robot3:robot1, robot2:robot1', [('robot3', 'robot1'), ('robot2', 'robot1')]),
    ('/robot2:/robot1', [('robot2', 'robot1')]),
])
def test_parse_pairs(text, pairs):
    assert parse_pairs(text, ['robot1', 'robot2', 'robot3']) == pairs


@pytest.mark.parametrize('text, message', [
    ('robot2', 'expected FOLLOWER:LEADER'),
    ('robot2:robot1:robot3', 'expected FOLLOWER:LEADER'),
    ('robot2:', 'expected FOLLOWER:LEADER'),
    ('robot2:robot1,', 'expected FOLLOWER:LEADER'),
    ('robot9:robot1', 'no pose topic for robot9 (robots: robot1, robot2, robot3)'),
    ('robot2:robot2', 'cannot follow itself'),
    ('robot2:robot1,robot2:robot3', 'robot2 already has a leader'),
])
def test_parse_pairs_rejects(text, message):
    with pytest.raises(ValueError, match=message.replace('(', r'\(').replace(')', r'\)')):
        parse_pairs(text, ['robot1', 'robot2', 'robot3'])


def _track(t0, t1, dt, x_of_t, y=0.0):
    n = round((t1 - t0) / dt)
    return [(t0 + i * dt, x_of_t(t0 + i * dt), y) for i in range(n + 1)]


def test_report_window_starts_when_every_robot_has_a_pose():
    # robot1 drives along x at 1 m/s from t = 0; robot2 appears at t = 1 s, 2 m behind it,
    # and keeps that gap; robot3 appears at t = 2 s, 1 m behind robot2.
    tracks = {
        'robot1': _track(0.0, 10.0, 0.5, lambda t: t),
        'robot2': _track(1.0, 10.0, 0.5, lambda t: t - 2.0),
        'robot3': _track(2.0, 10.0, 0.5, lambda t: t - 3.0),
    }
    report = report_pairs(tracks, chain_pairs(tracks), threshold_m=2.0)
    assert report.start_s == pytest.approx(2.0, abs=TOL)
    assert report.duration_s == pytest.approx(8.0, abs=TOL)
    assert [(p.follower, p.leader) for p in report.pairs] == [('robot2', 'robot1'),
                                                              ('robot3', 'robot2')]
    first, second = report.pairs
    assert first.stats.mean_gap_m == pytest.approx(2.0, abs=TOL)
    assert first.stats.max_gap_m == pytest.approx(2.0, abs=TOL)
    assert second.stats.mean_gap_m == pytest.approx(1.0, abs=TOL)
    assert first.gaps[0] == pytest.approx((0.0, 2.0), abs=TOL)
    assert all(s[0] >= 2.0 for samples in report.tracks.values() for s in samples)
    assert len(report.tracks['robot1']) == 17  # t = 2.0 .. 10.0 every 0.5 s


def test_report_pairs_with_newest_leader_sample():
    # The leader jumps 3 m at t = 1.0; the follower sampled at 0.9 still sees the old pose.
    tracks = {'a': [(0.0, 0.0, 0.0), (1.0, 3.0, 4.0)],
              'b': [(0.0, 0.0, 0.0), (0.9, 0.0, 0.0), (1.1, 0.0, 0.0)]}
    report = report_pairs(tracks, [('b', 'a')], threshold_m=1.0)
    assert [g for _, g in report.pairs[0].gaps] == pytest.approx([0.0, 0.0, 5.0], abs=TOL)
    assert report.pairs[0].stats.max_gap_m == pytest.approx(5.0, abs=TOL)


def test_report_only_the_robots_of_the_pairs_set_the_window():
    tracks = {'robot1': _track(0.0, 4.0, 1.0, lambda t: t),
              'robot2': _track(0.0, 4.0, 1.0, lambda t: t - 1.0),
              'robot3': _track(3.0, 4.0, 1.0, lambda t: 0.0)}
    report = report_pairs(tracks, [('robot2', 'robot1')], threshold_m=2.0)
    assert report.start_s == 0.0
    assert set(report.tracks) == {'robot1', 'robot2'}


@pytest.mark.parametrize('tracks, pairs, message', [
    ({'robot1': [(0.0, 0.0, 0.0)]}, [], 'at least two robots'),
    ({'robot1': [(0.0, 0.0, 0.0)], 'robot2': []}, [('robot2', 'robot1')],
     'no pose samples for robot2'),
    ({'robot1': [(0.0, 0.0, 0.0)]}, [('robot2', 'robot1')], 'no pose samples for robot2'),
    ({'robot1': [(0.0, 0.0, 0.0), (1.0, math.nan, 0.0)], 'robot2': [(0.0, 0.0, 0.0)]},
     [('robot2', 'robot1')], 'finite'),
])
def test_report_pairs_rejects(tracks, pairs, message):
    with pytest.raises(ValueError, match=message):
        report_pairs(tracks, pairs, threshold_m=2.0)


def test_report_pairs_rejects_a_follower_that_ends_before_the_window():
    # The window starts at the last first sample (1.0 s): robot2's only sample is before it.
    tracks = {'robot1': [(1.0, 0.0, 0.0)], 'robot2': [(0.0, 0.0, 0.0)]}
    with pytest.raises(ValueError,
                       match=r'no pose from robot2 once every robot has one \(t = 1.000 s\)'):
        report_pairs(tracks, [('robot2', 'robot1')], threshold_m=2.0)


def test_report_pairs_a_follower_with_the_leader_pose_from_before_the_window():
    # robot2 appears at 1.6 s; robot1's newest pose then is the one of 1.0 s (x = 1).
    tracks = {'robot1': [(0.0, 0.0, 0.0), (1.0, 1.0, 0.0), (2.0, 2.0, 0.0)],
              'robot2': [(1.6, 4.0, 0.0)]}
    report = report_pairs(tracks, [('robot2', 'robot1')], threshold_m=2.0)
    assert report.start_s == pytest.approx(1.6, abs=TOL)
    assert report.pairs[0].gaps == [pytest.approx((0.0, 3.0), abs=TOL)]


@pytest.mark.parametrize('threshold', [0.0, -1.0, math.inf, math.nan])
def test_report_pairs_rejects_bad_threshold(threshold):
    tracks = {'robot1': [(0.0, 0.0, 0.0)], 'robot2': [(0.0, 1.0, 0.0)]}
    with pytest.raises(ValueError, match='threshold_m'):
        report_pairs(tracks, [('robot2', 'robot1')], threshold)


def test_table_lines():
    # robot2 starts at x = -5, 5 m behind the leader at 0, and closes in at 1 m/s for 3 s.
    tracks = {'robot1': _track(0.0, 4.0, 1.0, lambda t: 0.0),
              'robot2': _track(0.0, 4.0, 1.0, lambda t: -5.0 + min(t, 3.0)),
              'robot3': _track(0.0, 4.0, 1.0, lambda t: -20.0)}
    report = report_pairs(tracks, chain_pairs(tracks), threshold_m=2.0)
    assert table_lines(report) == [
        '| follower | mean gap (m) | max gap (m) | within 2.0 m | catch-up |',
        '|---|---|---|---|---|',
        '| robot2 -> robot1 | 3.20 | 5.00 | 40 % | 3.0 s |',  # gaps 5, 4, 3, 2, 2
        '| robot3 -> robot2 | 16.80 | 18.00 | 0 % | never (within 4 s) |',  # 15 .. 18
    ]
