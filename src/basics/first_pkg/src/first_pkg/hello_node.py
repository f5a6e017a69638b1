"""The basics deck's first node (hello): logs "hello world <count>" at 10 Hz."""
import rospy
from course_common.startup import init_node, loop_at_rate

RATE_HZ = 10  # the slide's ros::Rate loop_rate(10)
# The slide's code streams "hello world" << count, which would print "hello world0"; the
# decks' screens (and the talker) read "hello world 0", so the space is kept here.
LINE = 'hello world %d'


class HelloNode:
    """Logs one line per cycle with a count that starts at 0.

    Subscribes: none. Publishes: only its log lines (on /rosout, as every node).
    Services: none. Parameters: none.
    """

    def __init__(self):
        self.count = 0

    def cycle(self):
        """One turn of the slide's while (ros::ok()) loop."""
        rospy.loginfo(LINE, self.count)
        self.count += 1


def main():
    """Entry point of hello."""
    init_node('hello')
    loop_at_rate(RATE_HZ, HelloNode().cycle)
