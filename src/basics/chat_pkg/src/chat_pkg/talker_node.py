"""The basics deck's talker: publishes "hello world <count>" on chatter at 10 Hz."""
import rospy
from course_common.startup import init_node, loop_at_rate
from std_msgs.msg import String

TOPIC = 'chatter'  # relative, as on the slide, so ns and remaps apply
QUEUE_SIZE = 1000  # the slide's node.advertise<std_msgs::String>("chatter", 1000)
RATE_HZ = 10  # the slide's ros::Rate loop_rate(10)
TEXT = 'hello world %d'  # the slide's ss << "hello world " << count


class Talker:
    """Publishes one counted String per cycle, from count 0, and logs it.

    Subscribes: none.
    Publishes: chatter (std_msgs/String, queue 1000): "hello world <count>" at 10 Hz.
    Services: none. Parameters: none.
    """

    def __init__(self):
        self._pub = rospy.Publisher(TOPIC, String, queue_size=QUEUE_SIZE)
        self.count = 0

    def cycle(self):
        """One turn of the slide's while (ros::ok()) loop."""
        msg = String(data=TEXT % self.count)
        rospy.loginfo('%s', msg.data)  # the slide's ROS_INFO("%s", msg.data.c_str())
        self._pub.publish(msg)
        self.count += 1


def main():
    """Entry point of talker (node name "talker"; __name:=talker1 renames it)."""
    init_node('talker')
    loop_at_rate(RATE_HZ, Talker().cycle)
