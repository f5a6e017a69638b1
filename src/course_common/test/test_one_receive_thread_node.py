#!/usr/bin/env python3
"""one_receive_thread() under a real master: what the subscriber receives is what rospy's own
threads would deliver (every message, in order per connection, with its connection header,
the latched one, a restarted publisher's), from one thread instead of one per connection;
deliver_bodies(): the messages' bodies instead, and a body refused closes the connection."""
import io
import os
import signal
import sys
import threading
import unittest

import rospy
import rostest
from course_common.publishers import unqueued_publisher
from course_common.rospy_internals import (
    caller_id,
    deliver_bodies,
    has_subscribers,
    one_receive_thread,
)
from course_common.testing import spawn, wait_for
from std_msgs.msg import String

DEADLINE_S = 30.0  # connections between processes on a loaded 2-core machine
TOPICS = 40        # rospy alone would give this node 40 receiving threads
MESSAGES = 25      # per topic
RECEIVE_THREAD = 'tcpros_receive'
# A publisher in a process of its own: 'RUN-<n>' ten times a second until killed.
TALKER = """
import sys, rospy
from std_msgs.msg import String
rospy.init_node('receive_thread_talker')
pub = rospy.Publisher('/shared/restart', String, queue_size=10)
n = 0
while not rospy.is_shutdown():
    pub.publish(String('%s-%d' % (sys.argv[1], n)))
    n += 1
    rospy.sleep(0.1)
"""


class Inbox:
    """Messages received on one topic and the threads that delivered them."""

    def __init__(self, topic, queue_size=1000):
        self._lock = threading.Lock()
        self._items = []
        self.threads = set()
        self.sub = rospy.Subscriber(topic, String, self._add, queue_size=queue_size)

    def _add(self, msg):
        with self._lock:
            self._items.append(msg)
            self.threads.add(threading.current_thread().name)

    def items(self):
        with self._lock:
            return list(self._items)


def receiving_threads():
    """Threads of this process now receiving for rospy subscriptions (named by topic)."""
    return [t.name for t in threading.enumerate() if t.name.startswith('/shared/')]


def _serialised(msg):
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


class OneReceiveThreadTest(unittest.TestCase):

    def test_many_topics_in_order_from_one_thread(self):
        names = ['/shared/many_%02d' % i for i in range(TOPICS)]
        pubs = [unqueued_publisher(n, String) for n in names]
        inboxes = [Inbox(n) for n in names]
        wait_for(lambda: all(has_subscribers(p) for p in pubs), DEADLINE_S,
                 'this node subscribed to its %d topics' % TOPICS)
        # rospy's connecting threads end once they hand their socket over
        wait_for(lambda: not receiving_threads(), DEADLINE_S,
                 'no thread left per connection (%s)' % receiving_threads()[:3])
        for k in range(MESSAGES):
            for i, pub in enumerate(pubs):
                pub.publish(String('%d %d' % (i, k)))
        wait_for(lambda: all(len(b.items()) >= MESSAGES for b in inboxes), DEADLINE_S,
                 'every message on every topic')
        for i, box in enumerate(inboxes):
            self.assertEqual([m.data for m in box.items()],
                             ['%d %d' % (i, k) for k in range(MESSAGES)])
            self.assertEqual(box.threads, {RECEIVE_THREAD})
            self.assertEqual(caller_id(box.items()[0]), rospy.get_name())
        self.assertEqual(receiving_threads(), [])
        for pub, box in zip(pubs, inboxes, strict=True):
            box.sub.unregister()
            pub.unregister()

    def test_latched_message_reaches_a_later_subscriber(self):
        pub = rospy.Publisher('/shared/latched', String, latch=True, queue_size=1)
        pub.publish(String('kept'))
        box = Inbox('/shared/latched')
        wait_for(box.items, DEADLINE_S, 'the latched message')
        self.assertEqual([m.data for m in box.items()], ['kept'])
        self.assertEqual(box.threads, {RECEIVE_THREAD})
        box.sub.unregister()
        pub.unregister()

    def test_bodies_delivered_in_order_and_a_refused_one_closes_the_connection(self):
        pub = unqueued_publisher('/shared/bodies', String)
        box = Inbox('/shared/bodies')   # the callback: for a connection handed back
        seen = []

        def take(bodies, _conn):
            if any(b.endswith(b'bad') for b in bodies):
                raise ValueError('not a message this handler takes')
            seen.append((threading.current_thread().name, [bytes(b) for b in bodies]))
        deliver_bodies(box.sub, take)
        wait_for(lambda: has_subscribers(pub), DEADLINE_S, 'the subscriber connected')
        for k in range(MESSAGES):
            pub.publish(String('body %d' % k))
        wait_for(lambda: sum(len(b) for _, b in seen) >= MESSAGES, DEADLINE_S,
                 'every body')
        bodies = [b for _, batch in seen for b in batch]
        self.assertEqual(bodies, [_serialised(String('body %d' % k)) for k in range(MESSAGES)])
        self.assertEqual({name for name, _ in seen}, {RECEIVE_THREAD})
        self.assertEqual(box.items(), [])       # no message object made
        pub.publish(String('bad'))
        # refused: the socket closed, rospy's own loop reconnects and calls the callback
        wait_for(lambda: (pub.publish(String('after')), box.items())[1], DEADLINE_S,
                 'a message through the reconnected connection')
        self.assertEqual(box.items()[0].data, 'after')
        box.sub.unregister()
        pub.unregister()

    def test_publisher_killed_and_started_again(self):
        box = Inbox('/shared/restart')

        def heard(run):
            return [m.data for m in box.items() if m.data.startswith(run + '-')]

        first = spawn([sys.executable, '-c', TALKER, 'FIRST'])
        self.addCleanup(first.stop)
        wait_for(lambda: len(heard('FIRST')) >= 3, DEADLINE_S, 'the first talker',
                 alive=first.alive)
        os.kill(first.proc.pid, signal.SIGKILL)  # no goodbye: the socket just ends
        first.wait_exit()
        # the ended connection goes back to rospy's loop, which closes it
        wait_for(lambda: box.sub.get_num_connections() == 0, DEADLINE_S,
                 "the killed talker's connection closed")
        second = spawn([sys.executable, '-c', TALKER, 'SECOND'])
        self.addCleanup(second.stop)
        wait_for(lambda: len(heard('SECOND')) >= 3, DEADLINE_S, 'the second talker',
                 alive=second.alive)
        numbers = [int(d.split('-')[1]) for d in heard('SECOND')]
        self.assertEqual(numbers, sorted(numbers))
        self.assertEqual(box.threads, {RECEIVE_THREAD})
        box.sub.unregister()


if __name__ == '__main__':
    one_receive_thread()
    rospy.init_node('one_receive_thread_test')
    rostest.rosrun('course_common', 'one_receive_thread', OneReceiveThreadTest)
