"""mimic: drive one turtle with the velocities another turtle's pose reports.

The top half is pure (topic resolution and the pose-to-command copy, unit-tested); the bottom
half is the node and main().
"""

import math

import rospy
from geometry_msgs.msg import Twist

from turtle_lite.msg import Pose
from turtle_lite.namespaces import append, remap, resolve_mappings, turtle_namespace
from turtle_lite.naming import validate_graph_name

INPUT_NS = "input"
OUTPUT_NS = "output"


def mimic_topics(namespace, node_name, mappings):
    """Full names of (input/pose, output/cmd_vel), resolved as roscpp's NodeHandles do.

    turtlesim's mimic creates NodeHandles "input" and "output", so a remap of the namespace
    itself (`input:=turtlesim1/turtle1`) moves the topics under it (TURTLESIM.md 1.9/1.13).
    namespace is the node's namespace, node_name its full name, mappings the command-line
    from:=to pairs. Raises ValueError for an invalid remapped name.
    """
    table = resolve_mappings(mappings, namespace, node_name)
    pose = remap(append(turtle_namespace(INPUT_NS, namespace, node_name, mappings), "pose"),
                 table)
    cmd_vel = remap(
        append(turtle_namespace(OUTPUT_NS, namespace, node_name, mappings), "cmd_vel"), table)
    # roscpp refuses an invalid remapped name at start-up; rospy would quietly use it.
    validate_graph_name(pose)
    validate_graph_name(cmd_vel)
    return pose, cmd_vel


def pose_to_command(linear_velocity, angular_velocity):
    """(linear_x, angular_z) for the follower: a copy of the leader's reported velocities.

    turtlesim's linear_velocity is a magnitude (never negative), so a reversing leader makes a
    forward-moving follower; that quirk is turtlesim's and is kept. Raises ValueError on a
    non-finite value (it would only poison the follower).
    """
    for name, value in (("linear_velocity", linear_velocity),
                        ("angular_velocity", angular_velocity)):
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {value!r}")
    return float(linear_velocity), float(angular_velocity)


class MimicNode:
    """Republishes the leader's pose velocities as the follower's cmd_vel.

    Subscribes:
        input/pose (turtle_lite/Pose, queue 1): the leader's pose.
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
            rospy.get_namespace(), rospy.get_name(), rospy.names.get_mappings())
    except ValueError as err:
        rospy.logfatal("mimic: bad input/output remapping: %s", err)
        raise SystemExit(1) from err
    rospy.loginfo("mimic: %s -> %s", pose_topic, cmd_vel_topic)
    node = MimicNode(pose_topic, cmd_vel_topic)
    rospy.on_shutdown(node.stop)
    rospy.spin()
