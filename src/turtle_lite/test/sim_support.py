"""Helpers shared by the turtlesim_node integration tests (rostest nodes)."""

import threading
import time

import rospy
from rosgraph_msgs.msg import Log

from turtle_lite.msg import Color, Pose

#: Deadlines for waits, generous because CI machines can be busy.
EVENT_DEADLINE_S = 10.0
START_DEADLINE_S = 30.0
#: float32 pose fields compared to this tolerance.
POSE_TOL = 1e-5
DEFAULT_BG = (69, 86, 255)
DEFAULT_PEN = (179, 184, 255)
CENTER = 5.5444446
WORLD = 11.088889


def wait_for(condition, timeout_s, what):
    """Poll ``condition`` until true; fail naming ``what`` after ``timeout_s``."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.005)
    raise AssertionError('timed out after %.1f s waiting for %s' % (timeout_s, what))


class Recorder:
    """Records every message of a topic, in arrival order, with its wall arrival time."""

    def __init__(self, topic, msg_class):
        self._lock = threading.Lock()
        self._items = []
        self.topic = topic
        self.sub = rospy.Subscriber(topic, msg_class, self._cb)

    def _cb(self, msg):
        with self._lock:
            self._items.append(msg)

    def clear(self):
        with self._lock:
            self._items = []

    def messages(self):
        with self._lock:
            return list(self._items)

    def count(self):
        with self._lock:
            return len(self._items)

    def latest(self):
        with self._lock:
            return self._items[-1] if self._items else None

    def wait_count(self, n, what=None):
        target = self.count() + n
        wait_for(lambda: self.count() >= target, EVENT_DEADLINE_S,
                 what or '%d more messages on %s' % (n, self.topic))
        return self.messages()

    def wait(self, predicate, what):
        """Wait for a message (arriving from now on) that satisfies ``predicate``."""
        start = self.count()

        def found():
            for msg in self.messages()[start:]:
                if predicate(msg):
                    return msg
            return None
        return wait_for(found, EVENT_DEADLINE_S, what)


class PoseRecorder(Recorder):
    def __init__(self, topic='/turtle1/pose'):
        super().__init__(topic, Pose)

    def wait_at_rest(self):
        return self.wait(lambda p: p.linear_velocity == 0 and p.angular_velocity == 0,
                         '%s at rest' % self.topic)


class ColorRecorder(Recorder):
    def __init__(self, topic='/turtle1/color_sensor'):
        super().__init__(topic, Color)

    def wait_rgb(self, rgb, what):
        return self.wait(lambda c: (c.r, c.g, c.b) == tuple(rgb), what)


class LogRecorder(Recorder):
    """/rosout messages of one node."""

    def __init__(self, node='/turtlesim'):
        self.node = node
        super().__init__('/rosout', Log)

    def lines(self, level=None):
        return [m.msg for m in self.messages()
                if m.name == self.node and (level is None or m.level == level)]

    def wait_line(self, text, level=None):
        """Wait until a line containing ``text`` has been logged; returns it."""
        def found():
            for line in self.lines(level):
                if text in line:
                    return line
            return None
        return wait_for(found, EVENT_DEADLINE_S, 'log line %r from %s' % (text, self.node))


def wait_connected(pub, what):
    wait_for(lambda: pub.get_num_connections() > 0, START_DEADLINE_S, what)


def published_topics():
    return {name for name, _ in rospy.get_published_topics()}


def graph_names():
    """(topics with a publisher or subscriber, services) registered on the master."""
    import rosgraph
    pubs, subs, srvs = rosgraph.Master('/sim_test').getSystemState()
    return ({t for t, _ in pubs} | {t for t, _ in subs}), {s for s, _ in srvs}
