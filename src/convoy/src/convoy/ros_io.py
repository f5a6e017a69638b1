"""ROS glue shared by the convoy nodes: commands out as Twist, poses in."""
import contextlib

import rospy
from course_common.planar import STOP, Pose
from geometry_msgs.msg import Twist


def pose_from_msg(msg):
    """A turtlesim/Pose message as a model planar Pose (not checked for finiteness)."""
    return Pose(float(msg.x), float(msg.y), float(msg.theta))


class CommandPublisher:
    """Publishes model Commands as geometry_msgs/Twist (linear.x, angular.z) on one topic."""

    def __init__(self, topic, queue_size):
        self._pub = rospy.Publisher(topic, Twist, queue_size=queue_size)

    def publish(self, command):
        """Publishes; a pose callback racing shutdown may find the publisher closed: ignored."""
        twist = Twist()
        twist.linear.x = command.linear_mps
        twist.angular.z = command.angular_radps
        try:
            self._pub.publish(twist)
        except (rospy.ROSException, ValueError):
            # rospy raises ROSException, or ValueError ("I/O operation on closed file") from
            # its closed buffer, when a callback publishes while the node shuts down.
            if not rospy.is_shutdown():
                raise

    def stop(self):
        """Sends one zero Twist; for rospy.on_shutdown, when the publisher may be closed."""
        with contextlib.suppress(rospy.ROSException, ValueError):
            self.publish(STOP)
