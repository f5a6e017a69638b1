"""capture.py's recording and decoding: each topic's raw messages as stageros sends them, then
the .npz's arrays, one row per step (checked: no step missing or twice, every stamp on the
step grid). Imported by capture.py from this folder (see its docstring)."""
import re
import struct

import numpy as np
import rospy
from course_common.angles import yaw_from_quaternion
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

BUFF_SIZE = 1 << 24  # rospy's receive buffer: read many scans per recv
STAMP_TOLERANCE_NS = 1_000_000  # a stamp must sit within 1 ms of its step's time
#: stageros's robot topics: /robot_<N>/name with several robots, /name with one (relative
#: names, root namespace); base_scan_<k> with several rangers.
ROBOT_TOPIC = re.compile(r'^(?:/robot_(\d+))?/(odom|base_pose_ground_truth|base_scan(?:_(\d+))?)$')
STAMP_OFFSET = 4  # bytes before header.stamp in Odometry and LaserScan (header.seq)


class CaptureError(Exception):
    """The capture failed; the message says why (and what stageros printed)."""


# --- recording ------------------------------------------------------------------------------
class Recorder:
    """Each topic's raw messages as they come ((stamp ns, bytes), in order), /clock's latest
    step, and a hook called with each new /clock step."""

    def __init__(self, interval_ns):
        self.interval_ns = interval_ns
        self.raw = {}
        self.last_step = {}
        self.on_clock = None
        self._subs = []

    def subscribe(self, topic, stamp_offset):
        self.raw[topic] = []
        self.last_step[topic] = 0
        self._subs.append(rospy.Subscriber(
            topic, rospy.AnyMsg, self._store, callback_args=(topic, stamp_offset),
            queue_size=None, buff_size=BUFF_SIZE, tcp_nodelay=True))

    def _store(self, msg, args):
        topic, offset = args
        secs, nsecs = struct.unpack_from('<2I', msg._buff, offset)
        stamp_ns = secs * 1_000_000_000 + nsecs
        self.raw[topic].append((stamp_ns, msg._buff))
        step = round(stamp_ns / self.interval_ns)
        self.last_step[topic] = max(self.last_step[topic], step)
        if topic == '/clock' and self.on_clock is not None:
            self.on_clock(step)

    def reached(self, step):
        return all(last >= step for last in self.last_step.values())

    def unsubscribe(self):
        for sub in self._subs:
            sub.unregister()


def robot_topics(published):
    """{topic: (robot, key)} of stageros's robot topics; key 'odom', 'gt' or 'scan<k>'."""
    topics = {}
    for topic in published:
        match = ROBOT_TOPIC.match(topic)
        if match:
            robot, name, k = match.groups()
            key = {'odom': 'odom', 'base_pose_ground_truth': 'gt'}.get(name, 'scan%s' % (k or 0))
            topics[topic] = (int(robot or 0), key)
    return topics


# --- decoding -------------------------------------------------------------------------------
def steps_of(topic, raw, interval_ns):
    """{step: bytes} of a topic's messages; CaptureError on a duplicate or an off-grid stamp."""
    by_step = {}
    for stamp_ns, buff in raw:
        step = round(stamp_ns / interval_ns)
        if abs(stamp_ns - step * interval_ns) > STAMP_TOLERANCE_NS:
            raise CaptureError('%s: stamp %d ns is not on the %g ms step grid (interval_sim?)'
                               % (topic, stamp_ns, interval_ns / 1e6))
        if step in by_step:
            raise CaptureError('%s: step %d received twice' % (topic, step))
        by_step[step] = buff
    return by_step


def check_steps(by_topic, last):
    """{topic: its first step}; CaptureError naming each gap after a topic's first step.

    A topic may start later than the others: real stageros publishes a scan only once its
    ranger has updated (a ranger updates every 100 ms; a world with `interval_sim 20` has no
    scan at steps 1-4)."""
    if not by_topic:
        raise CaptureError('nothing was recorded')
    gaps = []
    for topic, by_step in sorted(by_topic.items()):
        if not by_step:
            raise CaptureError('%s: no message at all' % topic)
        missing = [s for s in range(min(by_step), last + 1) if s not in by_step]
        if missing:
            gaps.append('%s: %d steps missing (%s%s)' % (topic, len(missing), missing[:10],
                                                         ' ...' if len(missing) > 10 else ''))
    if gaps:
        raise CaptureError('messages were dropped:\n  ' + '\n  '.join(gaps))
    return {topic: min(by_step) for topic, by_step in by_topic.items()}


def odometry_arrays(buffers):
    """(pose, twist): float64 (n, 3) arrays (x, y, yaw; vx, vy, wz) of Odometry messages."""
    pose, twist = [], []
    for buff in buffers:
        msg = Odometry()
        msg.deserialize(buff)
        p, q, t = msg.pose.pose.position, msg.pose.pose.orientation, msg.twist.twist
        pose.append((p.x, p.y, yaw_from_quaternion(q.x, q.y, q.z, q.w)))
        twist.append((t.linear.x, t.linear.y, t.angular.z))
    return np.array(pose, dtype=np.float64), np.array(twist, dtype=np.float64)


def scan_arrays(buffers):
    """(ranges, intensities, geom) of LaserScan messages: float32 (n, beams) twice and
    float64 (n, 4): angle_min, angle_increment, range_min, range_max."""
    ranges, intensities, geom = [], [], []
    for buff in buffers:
        msg = LaserScan()
        msg.deserialize_numpy(buff, np)
        ranges.append(msg.ranges)
        intensities.append(msg.intensities)
        geom.append((msg.angle_min, msg.angle_increment, msg.range_min, msg.range_max))
    return (np.array(ranges, dtype=np.float32), np.array(intensities, dtype=np.float32),
            np.array(geom, dtype=np.float64))


def capture_arrays(recorder, topics, last):
    """(arrays, late): the .npz's arrays from the recorded messages, steps first..last
    (checked), and {topic: first step} of the topics that start after the first step (their
    rows before it are NaN)."""
    interval_ns = recorder.interval_ns
    by_topic = {t: {s: b for s, b in steps_of(t, raw, interval_ns).items() if s <= last}
                for t, raw in recorder.raw.items()}
    firsts = check_steps(by_topic, last)
    first = min(firsts.values())
    arrays = {'steps': np.arange(first, last + 1, dtype=np.int32)}
    for topic, (robot, key) in sorted(topics.items()):
        buffers = [by_topic[topic][s] for s in range(firsts[topic], last + 1)]
        prefix = 'r%d_%s' % (robot, key)
        names = ('_ranges', '_intensities', '_geom') if key.startswith('scan') else (
            '_pose', '_twist')
        decoded = (scan_arrays if key.startswith('scan') else odometry_arrays)(buffers)
        for name, array in zip(names, decoded, strict=True):
            pad = np.full((firsts[topic] - first,) + array.shape[1:], np.nan, array.dtype)
            arrays[prefix + name] = np.concatenate([pad, array])
    return arrays, {t: f for t, f in sorted(firsts.items()) if f > first}
