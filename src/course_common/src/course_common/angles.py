"""The lessons' angle wrap: any finite angle into [-pi, pi) (pure, no rospy).

Units: radians. The result is the angle's representative in the half-open interval
[-pi, pi): +pi itself maps to -pi, as in the labs' ``np.mod(angle + pi, 2 pi) - pi``.

turtlesim's own heading wrap is not this one: it uses a truncated pi (3.14159265) and lives
with the simulator (turtle_lite.world.turtlesim_wrap_angle) so the simulator matches
turtlesim to the float. Lesson code (controllers, tests, benchmarks) wraps with this one.
"""
import math

from course_common.finite import is_finite_number

TWO_PI = 2.0 * math.pi


def wrap_angle(angle_rad):
    """angle_rad wrapped into [-pi, pi), in radians; the sign convention is unchanged
    (counter-clockwise positive). ValueError if it is not a finite number (bools refused).

    Used for heading errors: wrap_angle(target - heading) is the shortest turn to the target,
    positive to the left.
    """
    if not is_finite_number(angle_rad):
        raise ValueError('angle = %r: expected a finite number (rad)' % (angle_rad,))
    wrapped = (angle_rad + math.pi) % TWO_PI - math.pi
    # Rounding can land exactly on +pi (e.g. for -pi - 1e-17); keep the half-open interval.
    return -math.pi if wrapped >= math.pi else wrapped


def yaw_from_quaternion(x, y, z, w):
    """The rotation about z (rad, counter-clockwise positive, in [-pi, pi]) of the quaternion
    (x, y, z, w), as tf's euler_from_quaternion gives it: a planar robot's heading from a
    geometry_msgs/Quaternion (Stage's odometry). ValueError if a component is not finite.
    """
    for name, value in (('x', x), ('y', y), ('z', z), ('w', w)):
        if not is_finite_number(value):
            raise ValueError('quaternion %s = %r: expected a finite number' % (name, value))
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
