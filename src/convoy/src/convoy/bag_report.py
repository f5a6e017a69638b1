"""bag_report: the gap table and the figures of a convoy, from a bag that rosbag recorded.

rosrun convoy bag_report FILE.bag [--out DIR] [--pairs F:L,...] [--within M]
Reads every '<robot>/pose' topic of type turtlesim/Pose (ours, or the course's C++ convoy on
real turtlesim), pairs each follower with its leader (default: a chain in natural name order,
robot1 leading), prints each follower's mean and max distance to its leader, and writes
<stem>_trails.png and <stem>_gaps.png. Not a node: it needs no master. convoy_demo makes its
own table and figures with the same functions from the bag it records.
"""
import argparse
import os
import sys

import genpy
import rosbag
from course_common.pose_topics import POSE_TYPE, pose_topics

from convoy.control import DEFAULT_TOLERANCE_M
from convoy.plots import plot_gaps, plot_trails
from convoy.report import (
    chain_pairs,
    natural_key,
    parse_pairs,
    report_pairs,
    table_lines,
)

# "Caught up": within the course's tolerance plus half a metre of the leader.
DEFAULT_WITHIN_M = DEFAULT_TOLERANCE_M + 0.5


class BagError(ValueError):
    """The file is not a readable bag of a convoy; the message is the one line to print."""


def read_tracks(path):
    """{robot: [(t_s, x_m, y_m), ...]} from a bag, t the time rosbag received each pose.

    Poses carry no stamp, so the receive time is the only common clock of all robots.
    Raises BagError with a one-line reason.
    """
    try:
        with rosbag.Bag(path) as bag:
            info = bag.get_type_and_topic_info().topics
            by_topic = pose_topics({t: i.msg_type for t, i in info.items()})
            if not by_topic:
                raise BagError('%s: no <robot>/pose topic of type %s in this bag (topics: %s)'
                               % (path, POSE_TYPE, ', '.join(sorted(info)) or 'none'))
            tracks = {robot: [] for robot in by_topic.values()}
            for topic, msg, stamp in bag.read_messages(topics=list(by_topic)):
                tracks[by_topic[topic]].append((stamp.to_sec(), msg.x, msg.y))
    except rosbag.ROSBagUnindexedException:
        raise BagError('%s: the bag is unindexed (its recording did not end cleanly): '
                       'run "rosbag reindex %s" first' % (path, path)) from None
    except rosbag.ROSBagException as err:
        raise BagError('%s: not a readable bag file (%s)' % (path, err)) from None
    except genpy.DeserializationError as err:
        raise BagError('%s: a pose message cannot be read (%s)' % (path, err)) from None
    except OSError as err:
        raise BagError('%s: %s' % (path, err.strerror or err)) from None
    for samples in tracks.values():
        samples.sort(key=lambda s: s[0])  # chunks of a bag can overlap in time
    return tracks


def summarise_bag(path, pairs_text=None, within_m=DEFAULT_WITHIN_M):
    """convoy.report.ConvoyReport of a bag. Raises BagError."""
    tracks = read_tracks(path)
    try:
        pairs = parse_pairs(pairs_text, tracks) if pairs_text else chain_pairs(tracks)
        return report_pairs(tracks, pairs, within_m)
    except ValueError as err:
        raise BagError('%s: %s' % (path, err)) from None


def write_figures(report, out_dir, stem):
    """Writes <stem>_trails.png and <stem>_gaps.png into out_dir; returns their paths."""
    os.makedirs(out_dir, exist_ok=True)
    trails = os.path.join(out_dir, '%s_trails.png' % stem)
    gaps = os.path.join(out_dir, '%s_gaps.png' % stem)
    plot_trails(trails, report)
    plot_gaps(gaps, report, DEFAULT_TOLERANCE_M)
    return trails, gaps


def parse_args(argv):
    """Parses the command line (argparse exits 2 with a message on bad input)."""
    parser = argparse.ArgumentParser(
        prog='bag_report', description='Gap table and figures of a convoy from a rosbag: '
        "every <robot>/pose topic of type %s; each follower's distance to its leader." % POSE_TYPE)
    parser.add_argument('bag', help='the bag file, e.g. build/demo/convoy.bag')
    parser.add_argument('--out', help="directory for the PNGs (default: the bag's directory)")
    parser.add_argument('--pairs', help='FOLLOWER:LEADER,... (default: a chain in natural name '
                        'order, the first robot leading: robot2:robot1,robot3:robot2,...)')
    parser.add_argument('--within', type=float, default=DEFAULT_WITHIN_M,
                        help='"caught up" distance in m (default %(default)s: the course\'s '
                        'tolerance + 0.5)')
    args = parser.parse_args(argv)
    if not 0.0 < args.within < float('inf'):
        parser.error('--within must be a finite distance > 0 m, got %g' % args.within)
    return args


def main():
    """Entry point of bag_report: exit 0, 1 for a bag it cannot report on, 2 for bad usage."""
    args = parse_args(sys.argv[1:])
    try:
        report = summarise_bag(args.bag, args.pairs, args.within)
    except BagError as err:
        print('bag_report: error: %s' % err, file=sys.stderr)
        sys.exit(1)
    out = args.out or os.path.dirname(os.path.abspath(args.bag))
    stem = os.path.splitext(os.path.basename(args.bag))[0]
    trails, gaps = write_figures(report, out, stem)
    robots = sorted(report.tracks, key=natural_key)
    print('bag_report: %s: %d robots (%s), %.1f s from the first moment every one has a pose'
          % (args.bag, len(robots), ', '.join(robots), report.duration_s))
    print('\n' + '\n'.join(table_lines(report)))
    print('\ntrails: %s\ngaps:   %s' % (trails, gaps))
