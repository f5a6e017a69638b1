"""Lab 2 task one's arithmetic: the teleop command scaled for the Pioneer, and the simulator's
pose as the lab's Pose2D (pure, no rospy).

Units: m/s and rad/s for velocities, metres and radians for poses.
"""

from course_common.finite import is_finite_number

DEFAULT_DIVISOR = 4.0  # the lab's "robot_velocity.linear.x / 4"


def check_divisor(divisor):
    """The divisor as a float; ValueError unless it is a finite number > 0."""
    if not is_finite_number(divisor) or divisor <= 0.0:
        raise ValueError('divisor = %r: expected a finite number > 0' % (divisor,))
    return float(divisor)


def scale_twist(values, divisor=DEFAULT_DIVISOR):
    """The six Twist components (linear x, y, z, angular x, y, z) divided by `divisor`.

    The lab divides linear.x and angular.z, the only two a Pioneer (and the teleop) uses, and
    passes the other four on unchanged; here all six are divided, so a command with a sideways
    linear.y (which turtlesim does use) slows down too. ValueError if any value is not finite:
    such a command must never reach the robot.
    """
    values = tuple(float(v) for v in values)
    if len(values) != 6:
        raise ValueError('expected 6 Twist components, got %d' % len(values))
    if not all(is_finite_number(v) for v in values):
        raise ValueError('command has a non-finite component: %r' % (values,))
    divisor = check_divisor(divisor)
    return tuple(v / divisor for v in values)


def pose2d_fields(x, y, theta):
    """(x, y, theta) for geometry_msgs/Pose2D from a turtlesim pose, as the lab's CoppeliaSim
    script publishes it (theta = rotation about z). ValueError if any is not finite."""
    fields = (float(x), float(y), float(theta))
    if not all(is_finite_number(v) for v in fields):
        raise ValueError('pose has a non-finite field: x=%r, y=%r, theta=%r' % fields)
    return fields
