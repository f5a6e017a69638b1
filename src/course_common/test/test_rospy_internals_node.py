#!/usr/bin/env python3
"""Pins, on a real master, what course_common.rospy_internals relies on in the installed rospy.

Each failure names the rospy attribute, what it should do and rospy's version (pin()). The
checks that need no master are in unit/test_rospy_internals.py.
"""
import struct
import threading
import unittest

import rospy
import rostest
from course_common.rospy_internals import (
    caller_id,
    cheap_rosout,
    connection_ids,
    has_subscribers,
    name_mappings,
    tick_publisher,
    write_frame,
)
from course_common.testing import pin, wait_for
from rosgraph_msgs.msg import Log
from turtlesim.msg import Pose

DEADLINE_S = 30.0  # connections between processes on a loaded 2-core machine
# Values exact in float32, so a frame that arrives intact compares equal.
POSE = (1.5, -2.25, 0.125, 3.0, -0.5)
# One TCPROS frame of a turtlesim/Pose: 4-byte length, then five little-endian float32.
POSE_FRAME = struct.Struct('<I5f')
POSE_BYTES = 20
ECHO_NODES = {'/pinned_echo_a', '/pinned_echo_b'}


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

    def test_1_connections_one_per_subscriber_with_caller_ids(self):
        pub = tick_publisher('/pinned/pose', Pose)
        pin(pub.impl.queue_size is None, 'Publisher.impl.queue_size', 'can be cleared')
        wait_for(lambda: connection_ids(pub) == ECHO_NODES, DEADLINE_S,
                 'connections from %s (have %s)' % (sorted(ECHO_NODES), connection_ids(pub)))
        pin(len(pub.impl.connections) == 2, 'Publisher.impl.connections',
            'lists one connection per subscriber')
        pin(has_subscribers(pub), 'Publisher.impl.connections', 'is non-empty with subscribers')
        pin(all(not type(c).__name__.startswith('Queued') for c in pub.impl.connections),
            'Publisher.impl.queue_size = None', 'keeps connections unqueued')
        pub.unregister()

    def test_2_frames_written_arrive_intact_with_the_caller_id(self):
        pub = tick_publisher('/pinned/frames', Pose)
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
            got = (msg.x, msg.y, msg.theta, msg.linear_velocity, msg.angular_velocity)
            pin(got == POSE, 'TCPROSTransport.socket', 'carries frames written to it intact '
                '(sent %r, received %r)' % (POSE, got))
            pin(caller_id(msg) == rospy.get_name(), 'message._connection_header',
                "holds the publisher's callerid (got %r)" % caller_id(msg))
        pin(pub.impl.connections[0].stat_num_msg == sent + 3, 'TCPROSTransport.stat_num_msg',
            'counts messages')
        inbox.sub.unregister()
        pub.unregister()
        write_frame(pub, frame)  # unregistered: impl is None or closed, nothing is sent

    def test_3_remove_connection_takes_a_subscriber_out(self):
        pub = tick_publisher('/pinned/remove', Pose)
        inbox = Inbox('/pinned/remove', Pose)
        wait_for(lambda: has_subscribers(pub), DEADLINE_S, 'this node subscribed to itself')
        conn = pub.impl.connections[0]
        pub.impl.remove_connection(conn)
        conn.close()
        pin(not has_subscribers(pub), 'Publisher.impl.remove_connection()',
            'removes the connection from impl.connections')
        inbox.sub.unregister()
        pub.unregister()

    def test_4_cache_seed_stops_rosout_topic_listing(self):
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
        self.assertFalse(rospy.has_param('/rosout_disable_topics_generation'),
                         'the seed must stay local, off the parameter server')
        inbox.sub.unregister()

    def test_5_name_mappings_hold_the_argv_remaps(self):
        mappings = name_mappings()
        pin(mappings.get('pinned_from') == 'pinned_to', 'rospy.names.get_mappings()',
            'returns the remaps of the command line (got %r)' % mappings)


if __name__ == '__main__':
    rospy.init_node('test_rospy_internals')
    rostest.rosrun('course_common', 'rospy_internals', RospyInternalsTest)
