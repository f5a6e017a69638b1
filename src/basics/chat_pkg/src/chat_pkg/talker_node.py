"""The basics deck's talker: publishes "hello world <count>" on chatter at 10 Hz."""
import rospy
from course_common.startup import init_node
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

    def __init__(self, rate_hz=RATE_HZ):
        self._pub = rospy.Publisher(TOPIC, String, queue_size=QUEUE_SIZE)
        self._rate = rospy.Rate(rate_hz)
        self.count = 0

    def spin(self):
        """Loops until ROS shuts down (Ctrl-C), like the slide's while (ros::ok())."""
        while not rospy.is_shutdown():
            msg = String(data=TEXT % self.count)
            rospy.loginfo('%s', msg.data)  # the slide's ROS_INFO("%s", msg.data.c_str())
            self._pub.publish(msg)
            try:
                self._rate.sleep()
            except rospy.ROSInterruptException:
                return  # Ctrl-C during the sleep: a normal exit
            self.count += 1


def main():
    """Entry point of talker (node name "talker"; __name:=talker1 renames it)."""
    init_node('talker')
    Talker().spin()
