"""The lessons' planar robot model: a pose and a velocity command (pure, no rospy).

Frame and units, as turtlesim's: x, y in metres in the world frame (origin at the bottom
left, x right, y up); theta in radians, counter-clockwise from +x. A command is a forward
speed in m/s (positive forwards) and a turn rate in rad/s (positive counter-clockwise), the
linear.x and angular.z of a geometry_msgs/Twist.

Poses are not checked on construction: a pose made from a message may hold nan, and the
nodes decide what to do with it (is_finite_pose, check_pose).
"""
from dataclasses import dataclass

from course_common.finite import is_finite_number


@dataclass(frozen=True)
class Pose:
    """A planar pose: x, y in metres, theta in radians (geometry_msgs/Pose2D's fields)."""

    x: float
    y: float
    theta: float


@dataclass(frozen=True)
class Command:
    """A velocity command: forward speed (m/s) and turn rate (rad/s, counter-clockwise)."""

    linear_mps: float
    angular_radps: float


STOP = Command(0.0, 0.0)


def is_finite_pose(pose):
    """True if the pose's x, y and theta are all finite numbers (bools refused)."""
    return all(is_finite_number(v) for v in (pose.x, pose.y, pose.theta))


def check_pose(pose, what='pose'):
    """pose if is_finite_pose(pose); ValueError naming `what` and its fields otherwise."""
    if not is_finite_pose(pose):
        raise ValueError('%s (x=%r, y=%r, theta=%r) has a non-finite field: expected finite '
                         'numbers' % (what, pose.x, pose.y, pose.theta))
    return pose
