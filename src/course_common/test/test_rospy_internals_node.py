#!/usr/bin/env python3
"""Pins, on a real master, what course_common.rospy_internals relies on in the installed rospy.

Each failure names the rospy attribute, what it should do and rospy's version (pin()). The
checks that need no master are in unit/test_rospy_internals.py.
"""
import os
import signal
import struct
import sys
import threading
import unittest

import rosgraph
import rospy
import rostest
from course_common.publishers import unqueued_publisher
from course_common.rospy_internals import (
    caller_id,
    cheap_rosout,
    connection_ids,
    has_subscribers,
    name_mappings,
    pending_bytes,
    write_frame,
)
from course_common.testing import pin, spawn, wait_for
from geometry_msgs.msg import Pose2D as Pose
from rosgraph_msgs.msg import Log
from rospy.impl.tcpros_base import TCPROSTransport
from rospy.impl.tcpros_pubsub import QueuedConnection
from std_msgs.msg import String

DEADLINE_S = 30.0  # connections between processes on a loaded 2-core machine
# A frame that arrives intact compares equal.
POSE = (1.5, -2.25, 0.125)
# One TCPROS frame of a geometry_msgs/Pose2D: 4-byte length, then three little-endian float64.
POSE_FRAME = struct.Struct('<I3d')
POSE_BYTES = 24
ECHO_NODES = {'/pinned_echo_a', '/pinned_echo_b'}
# A subscriber in a process of its own, printing the sequence number that opens each
# std_msgs/String it receives and whether the rest of the message is intact.
STALL_LISTENER = """
import rospy
from std_msgs.msg import String
rospy.init_node('pinned_stall_listener')
def heard(msg):
    print(msg.data[:8], msg.data[8:] == 'x' * (len(msg.data) - 8), flush=True)
rospy.Subscriber('/pinned/stall', String, heard, queue_size=10000)
print('subscribed', flush=True)
rospy.spin()
"""
STALL_PAYLOAD = 'x' * 10000  # about a 1081-beam scan's size: buffers take part of a frame
MAX_STALL_FRAMES = 20000  # 200 MB: far beyond any socket buffer, the loop ends long before


def string_frame(seq):
    """A TCPROS frame of a std_msgs/String: '%08d' % seq, then STALL_PAYLOAD."""
    data = ('%08d' % seq + STALL_PAYLOAD).encode()
    body = struct.pack('<I', len(data)) + data
    return struct.pack('<I', len(body)) + body


class Inbox:
    """Messages received on one topic, with a lock (callbacks run in rospy's threads)."""

    def __init__(self, topic, msg_class):
        self._lock = threading.Lock()
        self._items = []
        self.sub = rospy.Subscriber(topic, msg_class, self._add, queue_size=100)

    def _add(self, msg):
        with self._lock:
            self._items.append(msg)

    def items(self):
        with self._lock:
            return list(self._items)


class RospyInternalsTest(unittest.TestCase):
    """Each test has topics of its own and cleans up its publishers and subscribers: any order."""

    def test_connections_plain_one_per_subscriber_with_caller_ids(self):
        pub = unqueued_publisher('/pinned/pose', Pose)
        wait_for(lambda: connection_ids(pub) == ECHO_NODES, DEADLINE_S,
                 'connections from %s (have %s)' % (sorted(ECHO_NODES), connection_ids(pub)))
        pin(len(pub.impl.connections) == 2, 'Publisher.impl.connections',
            'lists one connection per subscriber')
        pin(has_subscribers(pub), 'Publisher.impl.connections', 'is non-empty with subscribers')
        # rospy reads impl.queue_size when a subscriber connects: unqueued_publisher's is None,
        # so each connection is the transport itself (its socket is what write_frame writes to),
        # not a QueuedConnection (test_a_queued_publisher_wraps_its_connections).
        kinds = sorted(type(c).__name__ for c in pub.impl.connections)
        pin(all(isinstance(c, TCPROSTransport) and not isinstance(c, QueuedConnection)
                for c in pub.impl.connections), 'Publisher(queue_size=None).impl.connections',
            'makes the connections of new subscribers plain TCPROSTransports (got %s)' % kinds)
        pub.unregister()

    def test_a_queued_publisher_wraps_its_connections(self):
        # What unqueued_publisher saves, and why the check above can fail: with a queue_size,
        # rospy wraps each connection in a QueuedConnection (a thread per subscriber).
        pub = rospy.Publisher('/pinned/queued', Pose, queue_size=1)
        inbox = Inbox('/pinned/queued', Pose)
        wait_for(lambda: has_subscribers(pub), DEADLINE_S, 'this node subscribed to itself')
        kinds = sorted(type(c).__name__ for c in pub.impl.connections)
        pin(all(isinstance(c, QueuedConnection) for c in pub.impl.connections),
            'rospy.impl.tcpros_pubsub.QueuedConnection',
            'wraps the connections of a publisher with a queue_size (got %s)' % kinds)
        inbox.sub.unregister()
        pub.unregister()

    def test_frames_written_arrive_intact_with_the_caller_id(self):
        pub = unqueued_publisher('/pinned/frames', Pose)
        self.assertFalse(has_subscribers(pub))
        inbox = Inbox('/pinned/frames', Pose)
        wait_for(lambda: has_subscribers(pub), DEADLINE_S, 'this node subscribed to itself')
        frame = POSE_FRAME.pack(POSE_BYTES, *POSE)
        sent = pub.impl.connections[0].stat_num_msg
        # Several frames: the socket's buffers take them at once, none is dropped.
        for _ in range(3):
            write_frame(pub, frame)
        wait_for(lambda: len(inbox.items()) >= 3, DEADLINE_S, 'the three frames written')
        for msg in inbox.items():
            got = (msg.x, msg.y, msg.theta)
            pin(got == POSE, 'TCPROSTransport.socket', 'carries frames written to it intact '
                '(sent %r, received %r)' % (POSE, got))
            pin(caller_id(msg) == rospy.get_name(), 'message._connection_header',
                "holds the publisher's callerid (got %r)" % caller_id(msg))
        pin(pub.impl.connections[0].stat_num_msg == sent + 3, 'TCPROSTransport.stat_num_msg',
            'counts messages')
        inbox.sub.unregister()
        pub.unregister()
        write_frame(pub, frame)  # unregistered: impl is None or closed, nothing is sent

    def test_a_subscriber_that_stops_reading_keeps_its_connection_and_whole_messages(self):
        # A subscriber stopped (SIGSTOP: a suspended rostopic echo, a host whose cable is
        # out) while frames keep coming: its buffers fill, one frame goes out only in part,
        # later frames are dropped. Resumed, it must still be connected and hear whole
        # messages: the cut frame was finished first (rospy_internals.write_frame).
        pub = unqueued_publisher('/pinned/stall', String)
        listener = spawn([sys.executable, '-c', STALL_LISTENER])
        self.addCleanup(listener.stop)
        wait_for(lambda: has_subscribers(pub), DEADLINE_S, 'the stall listener to connect')
        conn = pub.impl.connections[0]
        os.kill(listener.pid, signal.SIGSTOP)
        try:
            for seq in range(MAX_STALL_FRAMES):
                write_frame(pub, string_frame(seq))
                if conn not in pub.impl.connections or pending_bytes(conn):
                    break
            else:
                self.fail('the buffers never took part of a frame in %d frames' % seq)
        finally:
            os.kill(listener.pid, signal.SIGCONT)
        pin(conn in pub.impl.connections, 'rospy_internals.write_frame',
            'keeps a subscriber whose buffers took part of a frame')
        resumed_at = seq + 1
        deadline_seq = resumed_at + MAX_STALL_FRAMES

        def heard_after_resume():
            nonlocal resumed_at
            if resumed_at < deadline_seq:
                write_frame(pub, string_frame(resumed_at))
                resumed_at += 1
            return any(line.split()[:1] and line.split()[0].isdigit()
                       and int(line.split()[0]) > seq for line in listener.lines())
        wait_for(heard_after_resume, DEADLINE_S, 'a message sent after the listener resumed',
                 alive=listener.alive)
        self.assertIn(conn, pub.impl.connections, 'the connection closed after the resume')
        heard = [line.split() for line in listener.lines() if line[:1].isdigit()]
        self.assertTrue(all(intact == 'True' for _, intact in heard), heard[-5:])
        numbers = [int(n) for n, _ in heard]
        self.assertEqual(numbers, sorted(numbers), 'messages out of order')
        pub.unregister()

    def test_remove_connection_takes_a_subscriber_out(self):
        pub = unqueued_publisher('/pinned/remove', Pose)
        inbox = Inbox('/pinned/remove', Pose)
        wait_for(lambda: has_subscribers(pub), DEADLINE_S, 'this node subscribed to itself')
        conn = pub.impl.connections[0]
        pub.impl.remove_connection(conn)
        conn.close()
        pin(not has_subscribers(pub), 'Publisher.impl.remove_connection()',
            'removes the connection from impl.connections')
        inbox.sub.unregister()
        pub.unregister()

    def test_cache_seed_stops_rosout_topic_listing(self):
        inbox = Inbox('/rosout', Log)
        wait_for(lambda: inbox.sub.get_num_connections() > 0, DEADLINE_S,
                 'this node subscribed to its own /rosout')

        def logged(text):
            found = [m for m in inbox.items() if m.name == rospy.get_name() and m.msg == text]
            return found[-1] if found else None

        # Without the seed rospy lists this node's topics in every Log (the test can fail).
        rospy.loginfo('pinned: before the seed')
        before = wait_for(lambda: logged('pinned: before the seed'), DEADLINE_S,
                          'the first log line on /rosout')
        self.assertIn('/rosout', before.topics)
        cheap_rosout()
        rospy.loginfo('pinned: after the seed')
        after = wait_for(lambda: logged('pinned: after the seed'), DEADLINE_S,
                         'the second log line on /rosout')
        pin(after.topics == [], 'rospy.impl.paramserver.get_param_server_cache()',
            'stops /rosout topic listing when /rosout_disable_topics_generation is seeded '
            '(topics: %r)' % after.topics)
        # The master itself (rospy.get_param would read the seeded cache) still holds the
        # parameter's default, false, from the workspace's roscore.xml
        self.assertIs(rosgraph.Master(rospy.get_name()).getParam(
            '/rosout_disable_topics_generation'), False,
            'the seed must stay local, off the parameter server')
        inbox.sub.unregister()

    def test_name_mappings_hold_the_argv_remaps(self):
        mappings = name_mappings()
        pin(mappings.get('pinned_from') == 'pinned_to', 'rospy.names.get_mappings()',
            'returns the remaps of the command line (got %r)' % mappings)


if __name__ == '__main__':
    rospy.init_node('test_rospy_internals')
    rostest.rosrun('course_common', 'rospy_internals', RospyInternalsTest)
