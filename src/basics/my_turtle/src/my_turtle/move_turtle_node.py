"""ROS node of the basics course's move_turtle: forward at 0.5 m/s, logging the pose."""
import contextlib

import rospy
from course_common.command_line import parse_argv_or_exit
from course_common.startup import init_node, loop_at_rate
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from my_turtle.robot_name import robot_from_args, robot_topics

FORWARD_SPEED_MPS = 0.5  # the slide's FORWARD_SPEED_MPS
RATE_HZ = 10  # the slide's ros::Rate rate(10)
QUEUE_SIZE = 10  # the slide's queue for the publisher and the subscriber


class MoveTurtleNode:
    """Drives one turtle straight ahead and logs its pose, as the slides' MoveTurtle.cpp.

    Subscribes:
        <robot>/pose (turtlesim/Pose, queue 10): each pose is logged as "x: %.2f, y: %.2f".
    Publishes:
        <robot>/cmd_vel (geometry_msgs/Twist, queue 10): linear.x = 0.5 m/s at 10 Hz; one zero
            Twist at shutdown.
    Services: none.
    Parameters: none. The robot is argv[1] (default turtle1); the names are relative, so
        remaps and ROS_NAMESPACE apply.
    """

    def __init__(self, robot):
        cmd_topic, pose_topic = robot_topics(robot)
        self._pub = rospy.Publisher(cmd_topic, Twist, queue_size=QUEUE_SIZE)
        # Subscribe last: the callback only logs, but keep the house order.
        self._sub = rospy.Subscriber(pose_topic, Pose, self._on_pose, queue_size=QUEUE_SIZE)

    @staticmethod
    def _on_pose(msg):
        rospy.loginfo('x: %.2f, y: %.2f', msg.x, msg.y)

    def run(self):
        """Publishes the forward command at 10 Hz until shutdown."""
        forward = Twist()
        forward.linear.x = FORWARD_SPEED_MPS
        rospy.loginfo('Starting to move forward')
        loop_at_rate(RATE_HZ, lambda: self._pub.publish(forward))

    def stop(self):
        """Sends one zero Twist (rospy.on_shutdown); the publisher may already be closed."""
        with contextlib.suppress(rospy.ROSException, ValueError):
            self._pub.publish(Twist())


def main():
    """Entry point of move_turtle: rosrun my_turtle move_turtle [ROBOT_NAME]."""
    # Before init_node, as multi_sync's nodes do: a bad command line needs no master.
    robot = parse_argv_or_exit(robot_from_args, label='move_turtle')
    init_node('move_turtle')
    cmd_topic, pose_topic = robot_topics(robot)
    rospy.loginfo('move_turtle: robot %s (publishes %s, subscribes %s)', robot,
                  rospy.resolve_name(cmd_topic), rospy.resolve_name(pose_topic))
    node = MoveTurtleNode(robot)
    rospy.on_shutdown(node.stop)
    node.run()
