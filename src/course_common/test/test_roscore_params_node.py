#!/usr/bin/env python3
"""The master of a sourced shell holds /rosout_disable_topics_generation (its default, false),
set by course_common's etc/ros/roscore.xml; so a plain rospy node (rospy.init_node, as the lab's
talker.py) keeps it in its cache after its first log line and never asks the master again.
While it is unset, each log line asks, holding the node's one master connection, and a Ctrl-C
then deadlocks the node's shutdown (README, "One master call per node")."""
import unittest

import rosgraph
import rospy
import rostest
from rospy.impl.paramserver import get_param_server_cache

PARAM = '/rosout_disable_topics_generation'


class TestRoscoreParams(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_roscore_params')  # plain rospy: no course_common.startup

    def test_the_master_holds_the_rosout_parameter_at_its_default(self):
        # the master itself: rospy.get_param reads the node's cache first
        self.assertIs(rosgraph.Master(rospy.get_name()).getParam(PARAM), False)

    def test_a_plain_rospy_node_caches_it_at_its_first_log_line(self):
        rospy.loginfo('a line')
        # rospy caches an unset parameter as {} and reads that as missing (asking again next
        # line); a set one it caches as its value.
        self.assertIs(get_param_server_cache().get(PARAM), False)


if __name__ == '__main__':
    rostest.rosrun('course_common', 'roscore_params', TestRoscoreParams)
