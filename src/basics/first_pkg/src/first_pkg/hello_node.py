"""The basics deck's first node (hello): logs "hello world <count>" at 10 Hz."""
import rospy
from course_common.startup import init_node

RATE_HZ = 10  # the slide's ros::Rate loop_rate(10)
# The slide's code streams "hello world" << count, which would print "hello world0"; the
# decks' screens (and the talker) read "hello world 0", so the space is kept here.
LINE = 'hello world %d'


class HelloNode:
    """Logs one line per cycle with a count that starts at 0.

    Subscribes: none. Publishes: only its log lines (on /rosout, as every node).
    Services: none. Parameters: none.
    """

    def __init__(self, rate_hz=RATE_HZ):
        self._rate = rospy.Rate(rate_hz)
        self.count = 0

    def spin(self):
        """Loops until ROS shuts down (Ctrl-C), like the slide's while (ros::ok())."""
        while not rospy.is_shutdown():
            rospy.loginfo(LINE, self.count)
            try:
                self._rate.sleep()
            except rospy.ROSInterruptException:
                return  # Ctrl-C during the sleep: a normal exit
            self.count += 1


def main():
    """Entry point of hello."""
    init_node('hello')
    HelloNode().spin()
