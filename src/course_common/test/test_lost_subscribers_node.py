#!/usr/bin/env python3
"""LostSubscribers against a real master: a subscriber that never connected is healed."""
import unittest

import rospy
import rostest
from course_common.publishers import LostSubscribers
from course_common.rospy_internals import connection_ids
from course_common.testing import wait_for
from course_common.testing.master import LostSubscriber
from std_msgs.msg import String

TOPIC = '/lost/topic'
LISTENER = '/lost_listener'   # registered at the master by hand: it never connects
DEADLINE_S = 30.0
PERIOD_S = 0.2


class TestLostSubscribers(unittest.TestCase):

    def test_a_listed_subscriber_that_never_connected_gets_the_publisher_again(self):
        pub = rospy.Publisher(TOPIC, String, queue_size=1)
        lost = LostSubscribers(pub, period_s=PERIOD_S)
        wait_for(lambda: '/lost_echo' in connection_ids(pub), DEADLINE_S, 'rostopic echo')
        with LostSubscriber(LISTENER, TOPIC, 'std_msgs/String') as listener:
            healed = wait_for(lost.check, DEADLINE_S, 'the lost subscriber found')
            self.assertEqual(healed, {LISTENER})   # not rostopic echo: it is connected
            wait_for(lambda: listener.told_of(rospy.get_node_uri()), DEADLINE_S,
                     "the master's publisherUpdate naming this publisher")
        pub.unregister()


if __name__ == '__main__':
    rospy.init_node('test_lost_subscribers')
    rostest.rosrun('course_common', 'lost_subscribers', TestLostSubscribers)
