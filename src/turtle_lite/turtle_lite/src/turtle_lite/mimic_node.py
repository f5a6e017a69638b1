"""mimic: drive one turtle with the velocities another turtle's pose reports.

The node only: the subscriber, the publisher and main(). Topic resolution and the
pose-to-command copy are the pure functions of mimic_relay.
"""

import rospy
from course_common.rospy_internals import name_mappings
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from turtle_lite.mimic_relay import mimic_topics, pose_to_command


class MimicNode:
    """Republishes the leader's pose velocities as the follower's cmd_vel.

    Subscribes:
        input/pose (turtlesim/Pose, queue 1): the leader's pose.
    Publishes:
        output/cmd_vel (geometry_msgs/Twist, queue 1): linear.x = pose.linear_velocity,
            angular.z = pose.angular_velocity, one per pose; one zero Twist on shutdown.
    `input` and `output` are namespaces: remap them (input:=turtlesim1/turtle1) to choose
    the turtles; the remap moves both topics as with turtlesim's roscpp NodeHandles.
    Parameters: none.
    """

    def __init__(self, pose_topic, cmd_vel_topic):
        self._pub = rospy.Publisher(cmd_vel_topic, Twist, queue_size=1)
        self._sub = rospy.Subscriber(pose_topic, Pose, self._on_pose, queue_size=1)

    def stop(self):
        self._pub.publish(Twist())

    def _on_pose(self, msg):
        try:
            linear, angular = pose_to_command(msg.linear_velocity, msg.angular_velocity)
        except ValueError as err:
            rospy.logwarn_throttle(1.0, "mimic: ignoring pose: %s", err)
            return
        twist = Twist()
        twist.linear.x = linear
        twist.angular.z = angular
        self._pub.publish(twist)


def main():
    rospy.init_node("turtle_mimic")
    try:
        pose_topic, cmd_vel_topic = mimic_topics(
            rospy.get_namespace(), rospy.get_name(), name_mappings())
    except ValueError as err:
        rospy.logfatal("mimic: bad input/output remapping: %s", err)
        raise SystemExit(1) from err
    rospy.loginfo("mimic: %s -> %s", pose_topic, cmd_vel_topic)
    node = MimicNode(pose_topic, cmd_vel_topic)
    rospy.on_shutdown(node.stop)
    rospy.spin()
