#!/usr/bin/env python
"""Lab 2's Python publisher (scripts/talker.py), written as the lab has students write it."""
import rospy
from std_msgs.msg import String


def talker():
    pub = rospy.Publisher('chatter', String, queue_size=10)
    # anonymous=True appends _<pid>_<ms> to the name: two talker.py can run side by side.
    rospy.init_node('talker', anonymous=True)
    rate = rospy.Rate(10)  # 10 Hz
    while not rospy.is_shutdown():
        hello_str = "hello world %s" % rospy.get_time()
        rospy.loginfo(hello_str)
        pub.publish(hello_str)
        rate.sleep()


if __name__ == '__main__':
    # The lab's shape: Ctrl-C during rate.sleep() raises, and ends the node quietly.
    try:  # noqa: SIM105 - the lab's try/except, as students type it
        talker()
    except rospy.ROSInterruptException:
        pass
