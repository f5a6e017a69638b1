"""ROS node standing in for the lab's CoppeliaSim script: the turtle's pose as Pose2D."""
import contextlib

import rospy
from course_common.startup import init_node
from geometry_msgs.msg import Pose2D
from turtlesim.msg import Pose

from pioneer_mover.relay import pose2d_fields

QUEUE_SIZE = 1  # only the newest pose matters to a controller
WARN_PERIOD_S = 5.0  # throttle for repeated bad-input warnings


class PoseBridgeNode:
    """Publishes the simulated Pioneer's pose as geometry_msgs/Pose2D, one per turtle pose.

    The lab's CoppeliaSim script publishes the robot's x, y and yaw as Pose2D on
    /pioneer/pose; here the turtle's turtlesim/Pose is converted (62.5 Hz). A pose with a NaN
    or infinite field is dropped with a throttled warning.

    Subscribes:
        turtle_pose (turtlesim/Pose, queue 1): the simulator's pose of the Pioneer turtle.
    Publishes:
        pose (geometry_msgs/Pose2D, queue 1): x, y in metres, theta in radians.
    Services: none.
    Parameters: none. Both names are relative: pioneer.launch starts the node in /pioneer.
    """

    def __init__(self):
        self._pub = rospy.Publisher('pose', Pose2D, queue_size=QUEUE_SIZE)
        # Subscribe last: the callback publishes.
        self._sub = rospy.Subscriber('turtle_pose', Pose, self._on_pose, queue_size=QUEUE_SIZE)

    def _on_pose(self, msg):
        try:
            x, y, theta = pose2d_fields(msg.x, msg.y, msg.theta)
        except ValueError as err:
            rospy.logwarn_throttle(WARN_PERIOD_S, 'pose_bridge: dropping %s' % err)
            return
        with contextlib.suppress(rospy.ROSException, ValueError):
            self._pub.publish(Pose2D(x=x, y=y, theta=theta))


def main():
    """Entry point of pose_bridge."""
    init_node('pose_bridge')
    rospy.loginfo('pose_bridge: %s (turtlesim/Pose) -> %s (geometry_msgs/Pose2D)',
                  rospy.resolve_name('turtle_pose'), rospy.resolve_name('pose'))
    PoseBridgeNode()
    rospy.spin()
