"""Recorders: what a test hears on a topic, and on /rosout, in arrival order.

Recorder keeps a topic's messages (optionally only those `accept` lets through, only the
newest `keep`), each with the caller id of its publisher; LogRecorder is a Recorder of
/rosout that first connects to every node that logs, so no later line can be missed.
stamp_ns reads a recorded message's stamp as an exact integer (simulated time compares
exactly: stageros stamps whole 100 ms steps).
"""
import threading

import rospy
from rosgraph_msgs.msg import Log

from course_common.rospy_internals import caller_id
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, wait_for
from course_common.testing.master import publishers_of


def stamp_ns(msg):
    """The stamp of msg in integer nanoseconds: its header's, or a rosgraph_msgs/Clock's."""
    return (msg.header.stamp if hasattr(msg, 'header') else msg.clock).to_nsec()


class Recorder:
    """Records the messages of a topic in arrival order (the newest `keep`, or all).

    accept: a predicate; messages it rejects are not kept (e.g. only INFO lines).
    """

    def __init__(self, topic, msg_class, keep=None, queue_size=None, accept=None):
        self._lock = threading.Lock()
        self._items = []  # (publisher's caller id, message)
        self._keep = keep
        self._accept = accept
        self.topic = topic
        self.sub = rospy.Subscriber(topic, msg_class, self._cb, queue_size=queue_size)

    def _cb(self, msg):
        if self._accept is not None and not self._accept(msg):
            return
        with self._lock:
            self._items.append((caller_id(msg), msg))
            if self._keep is not None:
                del self._items[:-self._keep]

    def clear(self):
        with self._lock:
            self._items = []

    def messages(self, publisher=None):
        """The messages so far (those of one publishing node, by name, if given)."""
        with self._lock:
            return [m for who, m in self._items if publisher is None or who == publisher]

    def data(self, publisher=None):
        """The data fields of the messages so far (std_msgs' one-field messages)."""
        return [m.data for m in self.messages(publisher)]

    def publishers(self):
        """The names of the nodes heard so far, in the order they were first heard."""
        with self._lock:
            return list(dict.fromkeys(who for who, _ in self._items))

    def count(self):
        with self._lock:
            return len(self._items)

    def latest(self):
        with self._lock:
            return self._items[-1][1] if self._items else None

    def close(self):
        self.sub.unregister()

    def wait_count(self, n, what=None, timeout_s=EVENT_DEADLINE_S):
        """Waits for n more messages; returns them all."""
        target = self.count() + n
        wait_for(lambda: self.count() >= target, timeout_s,
                 what or '%d more messages on %s' % (n, self.topic))
        return self.messages()

    def wait(self, predicate, what, timeout_s=EVENT_DEADLINE_S):
        """Waits for a message (arriving from now on) that satisfies predicate; returns it."""
        start = self.count()

        def found():
            return next((m for m in self.messages()[start:] if predicate(m)), None)
        return wait_for(found, timeout_s, what)

    def wait_latest(self, predicate, what, timeout_s=EVENT_DEADLINE_S):
        """Waits until the newest message satisfies predicate; returns it."""
        def check():
            msg = self.latest()
            return msg if msg is not None and predicate(msg) else None
        return wait_for(check, timeout_s, '%s on %s' % (what, self.topic))


class LogRecorder(Recorder):
    """/rosout lines (rostest runs no rosout aggregator), of one node by default.

    Construct it after the nodes of interest are up: it waits until it is connected to every
    node that publishes /rosout (connect=False: not), so their later lines cannot be missed.
    node: the node whose lines records(), lines() and the waits look at (None: every node).
    A line is kept once: rospy latches /rosout, so each new connection to a node re-sends its
    last line, and two connections can race as a node starts (the newer replaces the older,
    after both delivered that line); the copy has the same node, seq and stamp.
    """

    def __init__(self, node=None, accept=None, connect=True):
        self.node = node
        # (node, header.seq, header.stamp) of every line kept, clear() or not: a copy that
        # comes later is never a new line
        self._heard = set()
        super().__init__('/rosout', Log, queue_size=1000, accept=accept)
        if connect:
            wait_for(lambda: self.sub.get_num_connections() >= len(publishers_of('/rosout')),
                     START_DEADLINE_S, 'connections to every /rosout publisher')

    def _cb(self, msg):
        key = (msg.name, msg.header.seq, stamp_ns(msg))
        with self._lock:
            if key in self._heard:
                return
            self._heard.add(key)
        super()._cb(msg)

    def records(self, level=None, node=None):
        """The Log messages of the node (of `node` if given), at `level` if given."""
        node = node or self.node
        return [m for m in self.messages()
                if (node is None or m.name == node) and (level is None or m.level == level)]

    def lines(self, level=None, node=None):
        return [m.msg for m in self.records(level, node)]

    def wait_log(self, text, level=None, node=None, timeout_s=EVENT_DEADLINE_S):
        """Waits until a line containing text has been logged; returns its Log message."""
        def found():
            return next((m for m in self.records(level, node) if text in m.msg), None)
        return wait_for(found, timeout_s, 'log line %r from %s' % (text, node or self.node
                                                                    or 'any node'))

    def wait_line(self, text, level=None, node=None, timeout_s=EVENT_DEADLINE_S):
        """Waits until a line containing text has been logged; returns the line."""
        return self.wait_log(text, level, node, timeout_s).msg
