"""The basics deck's listener: logs "I heard: [<text>]" for every String on chatter."""
import rospy
from course_common.startup import init_node
from std_msgs.msg import String

TOPIC = 'chatter'  # relative, as on the slide, so ns and remaps apply
QUEUE_SIZE = 1000  # the slide's node.subscribe("chatter", 1000, chatterCallback)


class Listener:
    """Logs each message it hears, as the slide's chatterCallback does.

    Subscribes: chatter (std_msgs/String, queue 1000).
    Publishes: nothing but its log lines. Services: none. Parameters: none.
    """

    def __init__(self):
        self._sub = rospy.Subscriber(TOPIC, String, self._on_chatter, queue_size=QUEUE_SIZE)

    @staticmethod
    def _on_chatter(msg):
        rospy.loginfo('I heard: [%s]', msg.data)


def main():
    """Entry point of listener (node name "listener")."""
    init_node('listener')
    Listener()
    rospy.spin()
