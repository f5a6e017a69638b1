"""The Pioneer's two wheels, as Lab 2's CoppeliaSim script drives them (pure, no rospy).

The lab's script turns each Twist into the two wheels' speeds,
    vLeft  = v - (L/2) w
    vRight = v + (L/2) w,        L = 0.33 m (the lab's distance between the wheels),
and sets them as the wheel joints' target velocities. On Stage the robot takes a body
velocity, so the wheels are turned back into one:
    v = (vLeft + vRight) / 2,    w = (vRight - vLeft) / L.

Between the two, the wheels are held within the robot's limits (WheelLimits): no wheel faster
than the top speed, and no turn faster than the top turn rate. Both wheels are scaled by one
factor, so the robot keeps the path it was asked for (the ratio of the wheels, the curvature)
and only drives it more slowly; clipping one wheel alone would bend that path.

Units: m/s for speeds, rad/s for turn rates (counter-clockwise positive), metres for L.
"""
import math
from dataclasses import dataclass

from course_common.finite import finite_dataclass, is_finite_number

TRACK_WIDTH_M = 0.33  # the lab's L: "L = 0.33 -- m" in its subscriber_callback
# Stage 4.3's own Pioneer (worlds/pioneer.inc, pioneer_base's velocity_bounds
# [-0.5 0.5 0 0 0 0 -90.0 90.0]): 0.5 m/s forwards and backwards, 90 deg/s either way. A wheel
# at 0.5 m/s is the robot at 0.5 m/s straight ahead, so that is each wheel's top speed.
DEFAULT_MAX_WHEEL_MPS = 0.5
DEFAULT_MAX_TURN_RADPS = math.radians(90.0)


@finite_dataclass(low=0.0, low_open=True)
class WheelLimits:
    """A wheel's top speed (m/s) and the robot's top turn rate (rad/s), both > 0."""

    max_wheel_mps: float = DEFAULT_MAX_WHEEL_MPS
    max_turn_radps: float = DEFAULT_MAX_TURN_RADPS


PIONEER_LIMITS = WheelLimits()  # Stage's Pioneer 3-DX (pioneer.inc)


def check_track_width(track_m):
    """The distance between the wheels as a float; ValueError unless finite and > 0."""
    if not is_finite_number(track_m) or track_m <= 0.0:
        raise ValueError('track width = %r: expected a finite number > 0 (m)' % (track_m,))
    return float(track_m)


def _check_speeds(what, first, second):
    if not (is_finite_number(first) and is_finite_number(second)):
        raise ValueError('%s (%r, %r) has a non-finite component: expected finite numbers'
                         % (what, first, second))
    return float(first), float(second)


def wheel_speeds(linear_mps, angular_radps, track_m=TRACK_WIDTH_M):
    """(vLeft, vRight) in m/s for a forward speed and a turn rate: the lab's formula.

    ValueError if a speed is not finite or the track width is not > 0.
    """
    v, w = _check_speeds('command', linear_mps, angular_radps)
    half = check_track_width(track_m) / 2.0
    return v - half * w, v + half * w


def body_velocity(left_mps, right_mps, track_m=TRACK_WIDTH_M):
    """(v in m/s, w in rad/s) of the robot whose wheels turn at left_mps and right_mps: the
    inverse of wheel_speeds. ValueError if a speed is not finite or the track is not > 0."""
    left, right = _check_speeds('wheel speeds', left_mps, right_mps)
    return (left + right) / 2.0, (right - left) / check_track_width(track_m)


def limit_wheels(left_mps, right_mps, limits=PIONEER_LIMITS, track_m=TRACK_WIDTH_M):
    """(vLeft, vRight) scaled by one factor <= 1 so that neither wheel exceeds
    limits.max_wheel_mps and the turn (vRight - vLeft) / L does not exceed
    limits.max_turn_radps; unchanged when already within both. Signs and the ratio of the two
    wheels are kept (the same path, driven more slowly). ValueError on non-finite speeds."""
    left, right = _check_speeds('wheel speeds', left_mps, right_mps)
    track = check_track_width(track_m)
    scale = 1.0
    fastest = max(abs(left), abs(right))
    if fastest > limits.max_wheel_mps:
        scale = limits.max_wheel_mps / fastest
    turn = abs(right - left) / track
    if turn > limits.max_turn_radps:
        scale = min(scale, limits.max_turn_radps / turn)
    return left * scale, right * scale


@dataclass(frozen=True)
class Drive:
    """What the Pioneer does with one command: the wheels the lab's formula asks for, the
    wheels held within the limits, and the body velocity those make (for the simulator)."""

    asked_mps: tuple  # (vLeft, vRight) from the lab's formula
    wheels_mps: tuple  # (vLeft, vRight) within the limits
    linear_mps: float  # the robot's forward speed with those wheels
    angular_radps: float  # its turn rate, counter-clockwise positive

    @property
    def limited(self):
        """True if the limits slowed the wheels down."""
        return self.wheels_mps != self.asked_mps


def drive(linear_mps, angular_radps, limits=PIONEER_LIMITS, track_m=TRACK_WIDTH_M):
    """The Drive for a command: the lab's wheel speeds, held within limits, and the body
    velocity they make. ValueError if the command is not finite or the track is not > 0."""
    asked = wheel_speeds(linear_mps, angular_radps, track_m)
    wheels = limit_wheels(*asked, limits, track_m)
    return Drive(asked, wheels, *body_velocity(*wheels, track_m))
