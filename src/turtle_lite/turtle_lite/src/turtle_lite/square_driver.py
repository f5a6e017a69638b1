"""draw_square's state machine and goal maths, as turtlesim's draw_square (no ROS).

One SquareDriver.step() per timer tick turns the latest pose into the command to publish and
the log events; the node in draw_square_node.py owns the timer, the topics and the logging.
"""

import math
import struct
from dataclasses import dataclass
from enum import Enum

from course_common.finite import check_finite
from course_common.planar import Pose

# turtlesim's draw_square uses this truncated literal (#define PI 3.141592), not math.pi;
# it shows in the goal headings it logs (1.570796).
PI = 3.141592
SIDE_M = 2.0  # each goal lies this far ahead of where the turtle stopped
FORWARD_SPEED_MPS = 1.0
TURN_SPEED_RADPS = 0.4
POSITION_TOLERANCE_M = 0.1
HEADING_TOLERANCE_RAD = 0.01
STOPPED_THRESHOLD = 0.0001  # pose velocities below this count as stopped


class State(Enum):
    FORWARD = "FORWARD"
    STOP_FORWARD = "STOP_FORWARD"
    TURN = "TURN"
    STOP_TURN = "STOP_TURN"


@dataclass(frozen=True)
class Step:
    """What one tick decided.

    command: (linear_x, angular_z) to publish, or None to publish nothing this tick.
    reached: the turtle came to rest at the goal ("Reached goal").
    new_goal: a goal was set this tick ("New goal [...]"), else None: x, y in m, theta in rad,
        each rounded to float32 like turtlesim's Pose goal.
    """

    command: tuple = None
    reached: bool = False
    new_goal: Pose = None


def _f32(value):
    """Round to float32, as turtlesim stores its goal in a turtlesim::Pose."""
    return struct.unpack("f", struct.pack("f", value))[0]


def _goal_ahead(pose):
    return Pose(
        _f32(math.cos(pose.theta) * SIDE_M + pose.x),
        _f32(math.sin(pose.theta) * SIDE_M + pose.y),
        _f32(pose.theta),
    )


def _goal_turned(pose):
    # C's fmod keeps the sign of the dividend, as math.fmod does; then wrap into [-PI, PI).
    theta = math.fmod(pose.theta + PI / 2.0, 2 * PI)
    if theta >= PI:
        theta -= 2 * PI
    return Pose(_f32(pose.x), _f32(pose.y), _f32(theta))


def _check_pose(pose):
    for field in ("x", "y", "theta", "linear_velocity", "angular_velocity"):
        check_finite("pose." + field, getattr(pose, field))


class SquareDriver:
    """turtlesim's draw_square state machine, one step() per timer tick.

    FORWARD at 1 m/s until within 0.1 m / 0.01 rad of a goal 2 m ahead; STOP_FORWARD sends
    zero Twists until the pose reports both velocities < 0.0001, then the goal becomes the
    current heading + PI/2; TURN at 0.4 rad/s until that heading is reached; STOP_TURN waits
    for rest again and sets the next goal 2 m ahead. Each goal starts from where the turtle
    actually stopped, so the square drifts, exactly as turtlesim's does.
    """

    def __init__(self):
        self.state = State.FORWARD
        self.goal = None

    def _reached(self, pose):
        g = self.goal
        return (
            abs(_f32(pose.x - g.x)) < POSITION_TOLERANCE_M
            and abs(_f32(pose.y - g.y)) < POSITION_TOLERANCE_M
            and abs(_f32(pose.theta - g.theta)) < HEADING_TOLERANCE_RAD
        )

    @staticmethod
    def _stopped(pose):
        return (
            pose.angular_velocity < STOPPED_THRESHOLD
            and pose.linear_velocity < STOPPED_THRESHOLD
        )

    def step(self, pose):
        """Advance one tick given the latest pose (or None before the first pose).

        pose needs x, y, theta, linear_velocity, angular_velocity (a turtlesim Pose).
        Raises ValueError on a non-finite pose field.
        """
        if pose is None:
            return Step()
        _check_pose(pose)
        new_goal = None
        if self.goal is None:
            self.state = State.FORWARD
            self.goal = new_goal = _goal_ahead(pose)

        if self.state is State.FORWARD:
            if self._reached(pose):
                self.state = State.STOP_FORWARD
                return Step((0.0, 0.0), new_goal=new_goal)
            return Step((FORWARD_SPEED_MPS, 0.0), new_goal=new_goal)
        if self.state is State.TURN:
            if self._reached(pose):
                self.state = State.STOP_TURN
                return Step((0.0, 0.0))
            return Step((0.0, TURN_SPEED_RADPS))
        # STOP_FORWARD / STOP_TURN: hold still until the pose shows rest, then the next goal.
        if not self._stopped(pose):
            return Step((0.0, 0.0))
        if self.state is State.STOP_FORWARD:
            self.state = State.TURN
            self.goal = _goal_turned(pose)
        else:
            self.state = State.FORWARD
            self.goal = _goal_ahead(pose)
        return Step(None, reached=True, new_goal=self.goal)
