"""The convoy report from recorded poses: who follows whom, each follower's gap, the table.

Pure logic shared by bag_report and convoy_demo (no rospy, no rosbag). A track is one robot's
samples (t_s, x_m, y_m) in time order, as in convoy.metrics; a robot is named after the
namespace of its pose topic (/robot2/pose -> robot2: course_common.pose_topics).
"""
import re
from dataclasses import dataclass

from convoy.metrics import FollowerStats, follower_stats, gap_series

_DIGITS = re.compile(r'(\d+)')


def natural_key(name):
    """Sort key that puts robot2 before robot10 (numbers compare as numbers)."""
    return [(0, int(part), '') if part.isdigit() else (1, 0, part)
            for part in _DIGITS.split(name) if part]


def chain_pairs(robots):
    """(follower, leader) pairs of a chain in natural name order: robot1 leads, robot2 follows
    robot1, robot3 follows robot2, ... (the course's convoy.launch and convoy_chain.launch)."""
    ordered = sorted(robots, key=natural_key)
    return list(zip(ordered[1:], ordered[:-1], strict=True))


def parse_pairs(text, robots):
    """Pairs from 'robot2:robot1,robot3:robot2' (follower:leader, comma-separated).

    Raises ValueError naming the bad item: not follower:leader, a robot not in `robots`, a robot
    following itself, a follower listed twice.
    """
    known = set(robots)
    pairs, followers = [], set()
    for item in text.split(','):
        parts = [p.strip().strip('/') for p in item.split(':')]
        if len(parts) != 2 or not all(parts):
            raise ValueError('pair %r: expected FOLLOWER:LEADER, e.g. robot2:robot1' % item.strip())
        follower, leader = parts
        unknown = [r for r in parts if r not in known]
        if unknown:
            raise ValueError('pair %r: no pose topic for %s (robots: %s)'
                             % (item.strip(), ', '.join(unknown),
                                ', '.join(sorted(known, key=natural_key)) or 'none'))
        if follower == leader:
            raise ValueError('pair %r: a robot cannot follow itself' % item.strip())
        if follower in followers:
            raise ValueError('pair %r: %s already has a leader' % (item.strip(), follower))
        followers.add(follower)
        pairs.append((follower, leader))
    return pairs


@dataclass(frozen=True)
class PairReport:
    """One follower against its leader: statistics and the gap series (t from the start)."""

    follower: str
    leader: str
    stats: FollowerStats
    gaps: list  # (t_s since the report's start, gap_m)


@dataclass(frozen=True)
class ConvoyReport:
    """Every pair of a recording, over the window when every robot of the pairs has a pose."""

    start_s: float  # first time every robot has a pose (the tracks' clock)
    duration_s: float  # from start_s to the last sample
    threshold_m: float
    pairs: list  # of PairReport, in the order asked
    tracks: dict  # robot -> samples from start_s on (for the trails)


def report_pairs(tracks, pairs, threshold_m):
    """ConvoyReport of `pairs` ((follower, leader) names) over `tracks` (robot -> samples).

    The window starts at the first time every robot of the pairs has a sample; each follower
    sample in it is paired with its leader's newest sample at or before it (metrics.gap_series,
    so every follower sample has one).
    Raises ValueError: no pairs, a robot without samples, bad samples or threshold.
    """
    if not pairs:
        raise ValueError('no follower: a convoy needs at least two robots')
    robots = sorted({r for pair in pairs for r in pair}, key=natural_key)
    missing = [r for r in robots if not tracks.get(r)]
    if missing:
        raise ValueError('no pose samples for %s' % ', '.join(missing))
    start = max(tracks[r][0][0] for r in robots)
    end = max(tracks[r][-1][0] for r in robots)
    window = {r: [s for s in tracks[r] if s[0] >= start] for r in robots}
    ended = [r for r in robots if not window[r]]
    if ended:
        raise ValueError('no pose from %s once every robot has one (t = %.3f s)'
                         % (', '.join(ended), start))
    reports = []
    for follower, leader in pairs:
        # The whole leader track: its newest pose at the window's first instants may be older.
        gaps = gap_series(tracks[leader], window[follower])
        stats = follower_stats(tracks[leader], window[follower], threshold_m, t_origin_s=start)
        reports.append(PairReport(follower, leader, stats, [(t - start, g) for t, g in gaps]))
    return ConvoyReport(start, end - start, threshold_m, reports, window)


def table_lines(report):
    """The markdown table of a ConvoyReport, as convoy_demo and bag_report print it."""
    lines = ['| follower | mean gap (m) | max gap (m) | within %.1f m | catch-up |'
             % report.threshold_m,
             '|---|---|---|---|---|']
    for pair in report.pairs:
        stats = pair.stats
        catch_up = ('%.1f s' % stats.catch_up_s if stats.catch_up_s is not None
                    else 'never (within %.0f s)' % report.duration_s)
        lines.append('| %s -> %s | %.2f | %.2f | %.0f %% | %s |'
                     % (pair.follower, pair.leader, stats.mean_gap_m, stats.max_gap_m,
                        100.0 * stats.within_fraction, catch_up))
    return lines

