#!/usr/bin/env python3
"""LostSubscribers against a real master: a subscriber that never connected is healed."""
import threading
import unittest
from xmlrpc.server import SimpleXMLRPCServer

import rosgraph
import rospy
import rostest
from course_common.publishers import LostSubscribers
from course_common.rospy_internals import connection_ids
from course_common.testing import wait_for
from std_msgs.msg import String

TOPIC = '/lost/topic'
LISTENER = '/lost_listener'   # registered at the master by hand: it never connects
DEADLINE_S = 30.0
PERIOD_S = 0.2


class FakeListener:
    """An XML-RPC slave API that records the master's publisherUpdate calls and connects to
    nobody: a subscriber whose connection was lost."""

    def __init__(self):
        self.updates = []
        self.server = SimpleXMLRPCServer(('127.0.0.1', 0), logRequests=False, allow_none=True)
        self.server.register_function(self.publisherUpdate, 'publisherUpdate')
        self.server.register_function(lambda caller_id: [1, '', 1], 'getPid')
        self.uri = 'http://127.0.0.1:%d/' % self.server.server_address[1]
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def publisherUpdate(self, caller_id, topic, publishers):  # noqa: N802 (ROS's name)
        self.updates.append((topic, list(publishers)))
        return [1, '', 0]


class TestLostSubscribers(unittest.TestCase):

    def test_a_listed_subscriber_that_never_connected_gets_the_publisher_again(self):
        pub = rospy.Publisher(TOPIC, String, queue_size=1)
        lost = LostSubscribers(pub, period_s=PERIOD_S)
        wait_for(lambda: '/lost_echo' in connection_ids(pub), DEADLINE_S, 'rostopic echo')
        listener = FakeListener()
        master = rosgraph.Master(LISTENER)
        master.registerSubscriber(TOPIC, 'std_msgs/String', listener.uri)
        try:
            healed = wait_for(lost.check, DEADLINE_S, 'the lost subscriber found')
            self.assertEqual(healed, {LISTENER})   # not rostopic echo: it is connected
            wait_for(lambda: listener.updates, DEADLINE_S, "the master's publisherUpdate")
            topic, publishers = listener.updates[-1]
            self.assertEqual(topic, TOPIC)
            self.assertIn(rospy.get_node_uri(), publishers)
        finally:
            master.unregisterSubscriber(TOPIC, listener.uri)
            listener.server.shutdown()
        pub.unregister()


if __name__ == '__main__':
    rospy.init_node('test_lost_subscribers')
    rostest.rosrun('course_common', 'lost_subscribers', TestLostSubscribers)
