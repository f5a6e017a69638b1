"""The autopilot's closed path (a figure eight) and a pure-pursuit tracker on it; pure maths.

The path is a lemniscate of Gerono centred on the turtlesim world:
    p(s) = (cx + a*sin(s), cy + h*sin(2*s)),  s in [0, 2*pi)
It is closed (p(0) = p(2*pi)), smooth (p'(s) = (a*cos(s), 2*h*cos(2*s)) never vanishes), and
its crossing point is the world centre, where turtlesim puts turtle1: the leader starts on it.

Units: metres, radians, seconds; angles counter-clockwise from +x (turtlesim's frame).
"""
import math
from dataclasses import dataclass

from course_common.angles import wrap_angle
from course_common.arena import CENTRE_M, WORLD_SIZE_M
from course_common.finite import check_finite
from course_common.planar import Command, Pose, is_finite_pose

# Default figure eight: 9 m x 8 m, at least 1 m from every wall, 38.9 m long (78 s a lap).
# Large lobes on purpose: each follower cuts inside its leader's curves, so down a long chain
# the loops shrink; with 4 m x 2 m lobes the tail of a 10-robot chain ends up at a standstill.
DEFAULT_HALF_WIDTH_M = 4.5
DEFAULT_HALF_HEIGHT_M = 4.0
# Leader speed: the followers' steady gap on a straight is speed / Kp_lv = 1.67 m, just past the
# course's 1.5 m tolerance, so they keep moving instead of stopping and starting.
DEFAULT_SPEED_MPS = 0.5
DEFAULT_LOOKAHEAD_M = 0.8  # m: long enough to smooth the 16 ms pose steps, short enough to track
DEFAULT_MAX_TURN_RADPS = 2.0  # rad/s: the sharpest turn the autopilot asks for
# Window of the local search for the closest path point, in path parameter (radians of s).
_SEARCH_BACK = 0.2
_SEARCH_AHEAD = 0.6
_SEARCH_STEPS = 80
_GLOBAL_STEPS = 720


@dataclass(frozen=True)
class Lemniscate:
    """A figure eight p(s) = (cx + a sin s, cy + h sin 2s); raises ValueError if degenerate."""

    centre_x: float = CENTRE_M
    centre_y: float = CENTRE_M
    half_width: float = DEFAULT_HALF_WIDTH_M
    half_height: float = DEFAULT_HALF_HEIGHT_M

    def __post_init__(self):
        check_finite('centre_x', self.centre_x)
        check_finite('centre_y', self.centre_y)
        check_finite('half_width', self.half_width, low=0.0, low_open=True)
        check_finite('half_height', self.half_height, low=0.0, low_open=True)

    def point(self, s):
        """(x, y) of the path at parameter s."""
        return (self.centre_x + self.half_width * math.sin(s),
                self.centre_y + self.half_height * math.sin(2.0 * s))

    def heading(self, s):
        """Direction of travel (rad) at parameter s, for increasing s."""
        return math.atan2(2.0 * self.half_height * math.cos(2.0 * s),
                          self.half_width * math.cos(s))

    def bounds(self):
        """(x_min, x_max, y_min, y_max) of the path."""
        return (self.centre_x - self.half_width, self.centre_x + self.half_width,
                self.centre_y - self.half_height, self.centre_y + self.half_height)

    def fits_in_world(self, margin_m, world_size_m=WORLD_SIZE_M):
        """True if the whole path keeps at least margin_m from the world's walls."""
        x_min, x_max, y_min, y_max = self.bounds()
        return (x_min >= margin_m and y_min >= margin_m
                and x_max <= world_size_m - margin_m and y_max <= world_size_m - margin_m)


class PurePursuit:
    """Drives a unicycle along a Lemniscate at constant speed (pure pursuit).

    Keeps the path parameter of the closest point between calls, so at the crossing of the
    eight it carries straight on instead of jumping to the other branch.
    """

    def __init__(self, path, speed_mps=DEFAULT_SPEED_MPS, lookahead_m=DEFAULT_LOOKAHEAD_M,
                 max_turn_radps=DEFAULT_MAX_TURN_RADPS):
        self.path = path
        self.speed_mps = check_finite('speed_mps', speed_mps, low=0.0, low_open=True)
        self.lookahead_m = check_finite('lookahead_m', lookahead_m, low=0.0, low_open=True)
        self.max_turn_radps = check_finite('max_turn_radps', max_turn_radps, low=0.0,
                                           low_open=True)
        self.progress = None  # path parameter of the closest point; None before the first pose

    def _closest(self, pose):
        if self.progress is None:
            # First pose: the whole path, preferring the branch the robot already faces (at the
            # crossing two branches are equally close).
            candidates = [2.0 * math.pi * i / _GLOBAL_STEPS for i in range(_GLOBAL_STEPS)]

            def cost(s):
                px, py = self.path.point(s)
                turn = abs(wrap_angle(self.path.heading(s) - pose.theta))
                return math.hypot(px - pose.x, py - pose.y) + 0.5 * turn
        else:
            span = _SEARCH_BACK + _SEARCH_AHEAD
            candidates = [self.progress - _SEARCH_BACK + span * i / _SEARCH_STEPS
                          for i in range(_SEARCH_STEPS + 1)]

            def cost(s):
                px, py = self.path.point(s)
                return math.hypot(px - pose.x, py - pose.y)
        return min(candidates, key=cost)

    def command(self, pose):
        """The command for the robot at `pose` (a planar Pose). ValueError if it is not finite."""
        if not is_finite_pose(pose):
            raise ValueError('pose must be finite, got %r' % (pose,))
        s = self._closest(pose)
        self.progress = math.fmod(s, 2.0 * math.pi)
        # Walk forward from the closest point to the first point a lookahead away.
        target = self.path.point(s)
        step = 0.01
        for _ in range(int(2.0 * math.pi / step)):
            if math.hypot(target[0] - pose.x, target[1] - pose.y) >= self.lookahead_m:
                break
            s += step
            target = self.path.point(s)
        alpha = wrap_angle(math.atan2(target[1] - pose.y, target[0] - pose.x) - pose.theta)
        if abs(alpha) > math.pi / 2.0:
            # Facing away from the path (a start off the path): turn on the spot first.
            return Command(0.0, math.copysign(self.max_turn_radps, alpha))
        dist = max(math.hypot(target[0] - pose.x, target[1] - pose.y), 1e-6)
        turn = 2.0 * self.speed_mps * math.sin(alpha) / dist
        turn = max(-self.max_turn_radps, min(self.max_turn_radps, turn))
        return Command(self.speed_mps, turn)


def step_unicycle(pose, command, dt_s):
    """turtlesim's update: turn first, then move along the new heading (turtle.cpp)."""
    theta = wrap_angle(pose.theta + command.angular_radps * dt_s)
    return Pose(pose.x + math.cos(theta) * command.linear_mps * dt_s,
                pose.y + math.sin(theta) * command.linear_mps * dt_s,
                theta)
