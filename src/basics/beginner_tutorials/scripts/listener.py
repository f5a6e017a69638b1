#!/usr/bin/env python
"""Lab 2's Python subscriber (scripts/listener.py), written as the lab has students write it."""
import rospy
from std_msgs.msg import String


def callback(data):
    # The caller id is this node's own (anonymous) name, printed right before "I heard".
    rospy.loginfo(rospy.get_caller_id() + "I heard %s", data.data)


def listener():
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber("chatter", String, callback)
    rospy.spin()


if __name__ == '__main__':
    listener()
