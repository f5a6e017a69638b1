"""The convoy practice's follower control law, as a pure function (no rospy, no clock).

Course reference (convoy practice, "Nodo (III)" and "Nodo (controladores)"):
    d = hypot(xL - xF, yL - yF)
    if d >= tolerance:
        w = Kp_av * (atan2(yL - yF, xL - xF) - thetaF)
        v = 0 if |w| > 1 else Kp_lv * d
    else:
        v = w = 0                      (the follower stops)

One deliberate difference: the course does not wrap the heading error, so a follower whose
bearing to the leader lies across the +-pi seam turns almost a full circle the long way. Here
the error is wrapped into [-pi, pi) before the gain is applied, so it always turns the short way.

Units: metres, radians, seconds; angles counter-clockwise from +x (turtlesim's frame).
"""
import math

from course_common.angles import wrap_angle
from course_common.finite import finite_dataclass
from course_common.planar import STOP, Command, is_finite_pose

# The course's solution values.
DEFAULT_KP_LV = 0.3  # 1/s: forward speed per metre of distance
DEFAULT_KP_AV = 1.35  # 1/s: turn rate per radian of heading error
DEFAULT_TOLERANCE_M = 1.5  # m: closer than this the follower stops
# The course's literal: turning faster than 1 rad/s, the follower turns on the spot.
MAX_TURN_WHILE_DRIVING_RADPS = 1.0


@finite_dataclass(low=0.0)
class Gains:
    """The control law's constants, each finite and >= 0 (ValueError on construction)."""

    kp_lv: float = DEFAULT_KP_LV
    kp_av: float = DEFAULT_KP_AV
    tolerance_m: float = DEFAULT_TOLERANCE_M


def distance(leader, follower):
    """Euclidean distance between two poses, in metres."""
    return math.hypot(leader.x - follower.x, leader.y - follower.y)


def follow(leader, follower, gains=Gains()):
    """The course's command for `follower` to chase `leader`, with the heading error wrapped.

    Raises ValueError if either pose is not finite.
    """
    if not is_finite_pose(leader) or not is_finite_pose(follower):
        raise ValueError('poses must be finite, got leader=%r follower=%r' % (leader, follower))
    d = distance(leader, follower)
    if d < gains.tolerance_m:
        return STOP
    bearing = math.atan2(leader.y - follower.y, leader.x - follower.x)
    angular = gains.kp_av * wrap_angle(bearing - follower.theta)
    linear = 0.0 if abs(angular) > MAX_TURN_WHILE_DRIVING_RADPS else gains.kp_lv * d
    return Command(linear, angular)
