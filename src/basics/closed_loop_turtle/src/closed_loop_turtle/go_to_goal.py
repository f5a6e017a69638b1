"""Lab 2 task two's go-to-goal control law, as pure functions (no rospy, no clock).

The lab's code (move_turtle_to_goal.py) drives in two phases:
    position:     rho   = hypot(xg - x, yg - y)
                  alpha = wrap(atan2(yg - y, xg - x) - theta)
                  v = k_rho * rho,  w = k_alpha * alpha   until rho < 0.1 m ("Reach position")
    orientation:  beta  = theta - theta_g
                  v = 0,            w = k_beta * beta     until |beta| < 0.05 ("Reach orientation")
then one zero command. k_rho = 3.14, k_alpha = 5, k_beta = -3 (the lab's stability conditions:
k_rho > 0, k_beta < 0, k_alpha - k_rho > 0).

Differences from the lab, on purpose (each one in the package README):
- beta is wrapped into [-pi, pi) like alpha, so the robot turns the short way: the lab's
  unwrapped beta turns 2 pi - |beta| the long way whenever theta and theta_g lie more than pi
  apart (e.g. theta 3.0, theta_g -3.0: 6.0 rad instead of 0.28 rad);
- each speed is clipped to the robot's top speed; far from the goal that clips v far more than
  w, so the robot turns towards a goal behind it before driving off (the unlimited law sweeps
  an arc metres wide, out of the world);
- goals and poses are checked: non-finite values and goals outside the world raise GoalError.
One step of the law is `step()`; the node calls it at a fixed rate.

Units: metres, radians, seconds; angles counter-clockwise from +x (turtlesim's frame).
"""
import math
from dataclasses import dataclass
from enum import Enum

from course_common.angles import wrap_angle
from course_common.arena import WORLD_SIZE_M, inside
from course_common.finite import finite_dataclass
from course_common.planar import STOP, Command
from course_common.planar import check_pose as check_finite_pose

# The lab's values.
DEFAULT_K_RHO = 3.14  # 1/s: forward speed per metre of distance
DEFAULT_K_ALPHA = 5.0  # 1/s: turn rate per radian of bearing error
DEFAULT_K_BETA = -3.0  # 1/s: turn rate per radian of heading error (theta - theta_g)
DEFAULT_POSITION_TOLERANCE_M = 0.1  # the lab's "while not rho < 0.1"
DEFAULT_HEADING_TOLERANCE_RAD = 0.05  # the lab's "while not np.abs(beta) < 0.05"
# A Pioneer 3-DX's top speeds (datasheet: 1.2 m/s, 300 deg/s); the lab's law asks for up to
# k_rho * 15.7 m = 49 m/s across the turtle world.
DEFAULT_MAX_LINEAR_MPS = 1.2
DEFAULT_MAX_ANGULAR_RADPS = math.radians(300.0)


class GoalError(ValueError):
    """A goal or pose the controller refuses; the message says what was expected."""


@finite_dataclass
class Gains:
    """k_rho, k_alpha, k_beta; the lab's stability conditions are checked (ValueError)."""

    k_rho: float = DEFAULT_K_RHO
    k_alpha: float = DEFAULT_K_ALPHA
    k_beta: float = DEFAULT_K_BETA

    def __post_init__(self):
        # The lab's stability conditions, in its words (the node's FATAL line quotes them).
        if self.k_rho <= 0.0:
            raise ValueError('k_rho must be > 0, got %r' % self.k_rho)
        if self.k_beta >= 0.0:
            raise ValueError('k_beta must be < 0, got %r' % self.k_beta)
        if self.k_alpha - self.k_rho <= 0.0:
            raise ValueError('k_alpha must be greater than k_rho (%r), got %r'
                             % (self.k_rho, self.k_alpha))


@finite_dataclass(low=0.0, low_open=True)
class Tolerances:
    """When a goal counts as reached: distance (m) and heading error (rad), both > 0."""

    position_m: float = DEFAULT_POSITION_TOLERANCE_M
    heading_rad: float = DEFAULT_HEADING_TOLERANCE_RAD


@finite_dataclass(low=0.0, low_open=True)
class Limits:
    """Top speeds, both > 0: forward (m/s) and turn rate (rad/s)."""

    max_linear_mps: float = DEFAULT_MAX_LINEAR_MPS
    max_angular_radps: float = DEFAULT_MAX_ANGULAR_RADPS


class Phase(Enum):
    """Where the robot is in the lab's two-phase approach."""

    POSITION = 'position'
    ORIENTATION = 'orientation'
    ARRIVED = 'arrived'


@dataclass(frozen=True)
class Step:
    """The outcome of one control step: the next phase, the command, and what was reached."""

    phase: Phase
    command: Command
    reached_position: bool = False
    reached_orientation: bool = False


def check_pose(pose):
    """The pose if x, y and theta are finite; GoalError otherwise."""
    try:
        return check_finite_pose(pose)
    except ValueError as err:
        raise GoalError(str(err)) from None


def check_goal(goal, world_size_m=WORLD_SIZE_M):
    """The goal if finite and inside the world [0, world_size_m] x [0, world_size_m].

    GoalError otherwise, naming the goal and what was expected.
    """
    try:
        check_finite_pose(goal, 'goal')
    except ValueError as err:
        raise GoalError(str(err)) from None
    if not inside(goal.x, goal.y, world_size_m):
        raise GoalError('goal (x=%.3f, y=%.3f) is outside the world: expected 0 <= x, y <= %.3f m'
                        % (goal.x, goal.y, world_size_m))
    return goal


def position_error(pose, goal):
    """(rho, alpha): distance to the goal (m), its bearing from the heading (rad, wrapped)."""
    dx, dy = goal.x - pose.x, goal.y - pose.y
    return math.hypot(dx, dy), wrap_angle(math.atan2(dy, dx) - pose.theta)


def heading_error(pose, goal):
    """beta = wrap(theta - theta_g) in [-pi, pi) (the lab leaves it unwrapped)."""
    return wrap_angle(pose.theta - goal.theta)


def limit(command, limits):
    """The command with each speed clipped to its limit, sign kept.

    Clipped separately, not scaled together: far from a goal behind the robot the law asks for
    v = k_rho * rho (several m/s) and w = k_alpha * alpha; clipping v much harder than w makes
    the robot turn towards the goal first and then drive. Keeping the law's curvature instead
    sweeps an arc metres wide, out of the world (see the README's benchmark).
    """
    return Command(max(-limits.max_linear_mps, min(limits.max_linear_mps, command.linear_mps)),
                   max(-limits.max_angular_radps,
                       min(limits.max_angular_radps, command.angular_radps)))


def step(phase, pose, goal, gains=Gains(), tolerances=Tolerances(), limits=Limits()):
    """One step of the two-phase law from `phase` at `pose` towards `goal`.

    POSITION drives (v = k_rho rho, w = k_alpha alpha) until rho < position tolerance, then
    falls through to ORIENTATION in the same step, which turns on the spot (w = k_beta beta)
    until |beta| < heading tolerance; then ARRIVED with a STOP command. Once in ORIENTATION the
    robot does not go back to POSITION (as in the lab: v = 0 cannot move it away).
    """
    if phase is Phase.ARRIVED:
        return Step(Phase.ARRIVED, STOP)
    reached_position = False
    if phase is Phase.POSITION:
        rho, alpha = position_error(pose, goal)
        if rho >= tolerances.position_m:
            command = Command(gains.k_rho * rho, gains.k_alpha * alpha)
            return Step(Phase.POSITION, limit(command, limits))
        reached_position = True
    beta = heading_error(pose, goal)
    if abs(beta) >= tolerances.heading_rad:
        return Step(Phase.ORIENTATION, limit(Command(0.0, gains.k_beta * beta), limits),
                    reached_position=reached_position)
    return Step(Phase.ARRIVED, STOP, reached_position=reached_position, reached_orientation=True)
