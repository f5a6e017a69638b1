"""turtlesim's world: turtle state and the exact per-tick update, all turtles in one numpy step.

No rospy and no clock reads: the caller passes the wall time of each tick. Units are metres,
radians, seconds. Internally, like turtlesim, y is screen-style pointing down:
``y_s = H - y`` (turtlesim 0.10's turtle.cpp, ``Turtle::update``). Turtles are kept sorted
by name, which is turtlesim's ``std::map`` order, so wall warnings and trails come in the
same order.
"""

import math
from collections import namedtuple

import numpy as np

# The arena (canvas, scale, world size, turtle1's spawn point) is course_common.arena's: the
# lessons use the same numbers without importing the simulator.
from course_common.arena import CANVAS_PX, METER_PX, WORLD_SIZE_M
from course_common.finite import check_finite, is_finite_number

from .canvas import Canvas

#: The Qt timer interval that turtlesim also uses as dt; real elapsed time is never used.
DT_S = 0.016
#: turtlesim's truncated pi literal used in the heading wrap: result in [-P, P).
PI_TRUNC = 3.14159265
#: Commands older than this (wall time) stop the turtle.
CMD_TIMEOUT_S = 1.0
DEFAULT_BACKGROUND = (69, 86, 255)
DEFAULT_PEN_RGB = (179, 184, 255)
DEFAULT_PEN_WIDTH = 3
#: Largest accepted |velocity|: beyond it the float32 velocities of a Pose could overflow
#: to inf. turtlesim has no limit; this is ours. Positions and angles only have to be finite
#: (walls clamp positions, the wrap reduces angles).
MAX_ABS_VELOCITY = 1e15

Pose = namedtuple('Pose', 'x y theta linear_velocity angular_velocity')
WallHit = namedtuple('WallHit', 'name x y_s')
StepResult = namedtuple('StepResult', 'names poses colors wall_hits')
"""names: tuple of turtle names (sorted); poses: N x 5 float32 (x, y, theta, linear_velocity,
angular_velocity); colors: N x 3 uint8 (r, g, b); wall_hits: WallHit per turtle that was
clamped, with the unclamped internal x and y_s (the values turtlesim's WARN prints)."""

_FIELDS = ('x', 'ys', 'theta', 'vx', 'vy', 'w', 'last_cmd')


def turtlesim_wrap_angle(theta):
    """turtlesim's heading wrap: theta - 2P floor((theta + P) / 2P), P = 3.14159265.

    Not the lessons' course_common.angles.wrap_angle, on purpose: turtlesim wraps with a
    truncated pi, so headings near +-pi come out where turtlesim puts them (to the float32).
    Works on floats and arrays; the result lies in [-P, P). For huge |theta| (where the
    formula loses all precision) the value is first reduced exactly with fmod.
    """
    two_p = 2.0 * PI_TRUNC
    arr = np.asarray(theta, dtype=np.float64)
    out = arr - two_p * np.floor((arr + PI_TRUNC) / two_p)
    bad = ~((out >= -PI_TRUNC) & (out < PI_TRUNC))
    if np.any(bad):
        red = np.fmod(np.where(np.isfinite(arr), arr, 0.0), two_p)
        red = red - two_p * np.floor((red + PI_TRUNC) / two_p)
        red = np.where(red >= PI_TRUNC, red - two_p, red)
        red = np.where(red < -PI_TRUNC, red + two_p, red)
        out = np.where(bad, red, out)
    if np.ndim(theta) == 0:
        return float(out)
    return out


def _check_finite(label, value, limit=None):
    value = check_finite(label, float(value))
    if limit is not None and abs(value) > limit:
        raise ValueError('%s=%r is beyond +-%g' % (label, value, limit))
    return value


def _f32(value):
    """Round to float32, as turtlesim's float parameters do."""
    return float(np.float32(value))


def _finite_f32(label, value):
    """``value`` rounded to float32; ValueError if it is not finite before or after."""
    value = _check_finite(label, value)
    with np.errstate(over='ignore'):
        rounded = float(np.float32(value))
    if not is_finite_number(rounded):
        raise ValueError('%s=%r overflows a float32' % (label, value))
    return rounded


class World:
    """All turtles, the canvas, and turtlesim's update rule.

    Not thread-safe: the node serialises access with its own lock.
    """

    def __init__(self, background=DEFAULT_BACKGROUND):
        self.canvas = Canvas(background, CANVAS_PX, CANVAS_PX)
        self.names = []
        self._index = {}
        for f in _FIELDS:
            setattr(self, f, np.zeros(0, dtype=np.float64))
        self.pen_on = np.zeros(0, dtype=bool)
        self.pen_rgb = np.zeros((0, 3), dtype=np.uint8)
        self.pen_width = np.zeros(0, dtype=np.int64)
        self._teleports = {}
        #: True while something may change at the next step (motion, teleports, new turtles).
        self.active = False
        self._poses = np.zeros((0, 5), dtype=np.float32)
        self._colors = np.zeros((0, 3), dtype=np.uint8)
        self._sampled_version = -1

    # ------------------------------------------------------------------ turtles
    def __contains__(self, name):
        return name in self._index

    def __len__(self):
        return len(self.names)

    def add_turtle(self, name, x, y, theta):
        """Add a turtle at pose (x, y, theta); values are rounded to float32 like turtlesim.

        Nothing is validated or clamped here: an out-of-range turtle is clamped (with a wall
        hit) on its first step, as in turtlesim. Raises ValueError for a duplicate name or a
        non-finite value.
        """
        if name in self._index:
            raise ValueError('A turtled named [%s] already exists' % name)
        x = _finite_f32('x', x)
        y = _finite_f32('y', y)
        theta = _finite_f32('theta', theta)
        pos = int(np.searchsorted(np.array(self.names, dtype=object), name)) if self.names \
            else 0
        values = {'x': x, 'ys': WORLD_SIZE_M - y, 'theta': theta, 'vx': 0.0, 'vy': 0.0,
                  'w': 0.0, 'last_cmd': 0.0}
        for f in _FIELDS:
            setattr(self, f, np.insert(getattr(self, f), pos, values[f]))
        self.pen_on = np.insert(self.pen_on, pos, True)
        self.pen_rgb = np.insert(self.pen_rgb, pos, DEFAULT_PEN_RGB, axis=0)
        self.pen_width = np.insert(self.pen_width, pos, DEFAULT_PEN_WIDTH)
        self.names.insert(pos, name)
        self._reindex()
        self._teleports[name] = []
        self.active = True

    def remove_turtle(self, name):
        """Remove a turtle; raises KeyError (turtlesim's message) if there is none."""
        if name not in self._index:
            raise KeyError('Tried to kill turtle [%s], which does not exist' % name)
        i = self._index[name]
        for f in _FIELDS:
            setattr(self, f, np.delete(getattr(self, f), i))
        self.pen_on = np.delete(self.pen_on, i)
        self.pen_rgb = np.delete(self.pen_rgb, i, axis=0)
        self.pen_width = np.delete(self.pen_width, i)
        del self.names[i]
        del self._teleports[name]
        self._reindex()

    def remove_all(self):
        for name in list(self.names):
            self.remove_turtle(name)

    def _reindex(self):
        self._index = {n: i for i, n in enumerate(self.names)}

    def _i(self, name):
        try:
            return self._index[name]
        except KeyError:
            raise KeyError('no turtle named [%s]' % name) from None

    # ------------------------------------------------------------------ commands
    def set_command(self, name, vx, vy, w, now):
        """cmd_vel: set the velocities and the wall time of the last command.

        Raises ValueError (and changes nothing) if a value is not finite or beyond
        MAX_ABS_VELOCITY.
        """
        vx = _check_finite('linear.x', vx, MAX_ABS_VELOCITY)
        vy = _check_finite('linear.y', vy, MAX_ABS_VELOCITY)
        w = _check_finite('angular.z', w, MAX_ABS_VELOCITY)
        i = self._i(name)
        self.vx[i] = vx
        self.vy[i] = vy
        self.w[i] = w
        self.last_cmd[i] = now
        self.active = True

    def teleport_absolute(self, name, x, y, theta):
        """Queue an absolute teleport (applied at the next step). Values become float32."""
        req = ('abs', _finite_f32('x', x), _finite_f32('y', y), _finite_f32('theta', theta))
        self._i(name)
        self._teleports[name].append(req)
        self.active = True

    def teleport_relative(self, name, linear, angular):
        """Queue a relative teleport: rotate by ``angular``, then move ``linear`` metres."""
        req = ('rel', _finite_f32('linear', linear), _finite_f32('angular', angular))
        self._i(name)
        self._teleports[name].append(req)
        self.active = True

    def set_pen(self, name, r, g, b, width, off):
        """turtlesim's set_pen: off != 0 turns the pen off and keeps colour and width;
        otherwise the pen is on with (r, g, b) and ``width`` (0 means 1 px, Qt's default).

        The message fields are uint8; larger ints are masked to 8 bits here.
        """
        i = self._i(name)
        if off:
            self.pen_on[i] = False
            return
        self.pen_on[i] = True
        self.pen_rgb[i] = (int(r) & 0xFF, int(g) & 0xFF, int(b) & 0xFF)
        self.pen_width[i] = (int(width) & 0xFF) or 1

    def clear(self, background):
        """Fill the canvas with ``background``; turtles and pens are untouched."""
        self.canvas.fill(background)

    def pose(self, name):
        """Current pose of one turtle (float32 values, pose frame)."""
        i = self._i(name)
        return Pose(*(float(v) for v in self._pose_rows(np.array([i]))[0]))

    def poses_now(self):
        """N x 5 float32 poses of all turtles (sorted by name), as of now."""
        return self._pose_rows()

    def pen(self, name):
        """(pen_on, (r, g, b), width) of one turtle."""
        i = self._i(name)
        return bool(self.pen_on[i]), tuple(int(c) for c in self.pen_rgb[i]), \
            int(self.pen_width[i])

    # ------------------------------------------------------------------ the update
    def _pose_rows(self, idx=None):
        if idx is None:
            idx = slice(None)
        out = np.empty((len(self.x[idx]), 5), dtype=np.float32)
        out[:, 0] = self.x[idx]
        out[:, 1] = WORLD_SIZE_M - self.ys[idx]
        out[:, 2] = self.theta[idx]
        out[:, 3] = np.hypot(self.vx[idx], self.vy[idx])
        out[:, 4] = self.w[idx]
        return out

    def _apply_teleports(self):
        canvas = self.canvas
        for name, queue in self._teleports.items():
            if not queue:
                continue
            i = self._index[name]
            for req in queue:
                old_x, old_ys = self.x[i], self.ys[i]
                if req[0] == 'rel':
                    self.theta[i] += req[2]
                    self.x[i] += math.cos(self.theta[i]) * req[1]
                    self.ys[i] -= math.sin(self.theta[i]) * req[1]
                else:
                    self.x[i] = req[1]
                    self.ys[i] = max(0.0, WORLD_SIZE_M - req[2])
                    self.theta[i] = req[3]
                if self.pen_on[i]:
                    canvas.draw_line(self.x[i] * METER_PX, self.ys[i] * METER_PX,
                                     old_x * METER_PX, old_ys * METER_PX,
                                     self.pen_rgb[i], self.pen_width[i])
            queue.clear()

    def step(self, now, dt=DT_S):
        """One turtlesim tick at wall time ``now``: teleports, timeout, heading, position,
        walls, pose, colour, trail. Returns a StepResult.

        When nothing can change (no motion, no teleports, no new turtle) the previous poses
        and colours are returned without recomputing them.
        """
        n = len(self.names)
        if not self.active and self._poses.shape[0] == n:
            if self._sampled_version != self.canvas.version:
                self._colors = self.canvas.sample(self.x * METER_PX, self.ys * METER_PX)
                self._sampled_version = self.canvas.version
            return StepResult(tuple(self.names), self._poses, self._colors, [])

        self._apply_teleports()
        # Timeout: wall time since the last command.
        stale = (now - self.last_cmd) > CMD_TIMEOUT_S
        if stale.any():
            self.vx[stale] = 0.0
            self.vy[stale] = 0.0
            self.w[stale] = 0.0
        old_x = self.x.copy()
        old_ys = self.ys.copy()
        # Heading first, then position with the new heading (semi-implicit Euler).
        theta = turtlesim_wrap_angle(self.theta + self.w * dt)
        cos_t = np.cos(theta)
        sin_t = np.sin(theta)
        x = self.x + (cos_t * self.vx - sin_t * self.vy) * dt
        ys = self.ys - (cos_t * self.vy + sin_t * self.vx) * dt
        # Walls: turtlesim warns with the unclamped internal x and y_s, then clamps.
        hit = (x < 0.0) | (x > WORLD_SIZE_M) | (ys < 0.0) | (ys > WORLD_SIZE_M)
        wall_hits = []
        if hit.any():
            for i in np.flatnonzero(hit):
                wall_hits.append(WallHit(self.names[i], float(x[i]), float(ys[i])))
            x = np.minimum(np.maximum(x, 0.0), WORLD_SIZE_M)
            ys = np.minimum(np.maximum(ys, 0.0), WORLD_SIZE_M)
        self.theta = theta
        self.x = x
        self.ys = ys

        poses = self._pose_rows()
        # Colour under each turtle, sampled before this tick's trail is drawn.
        colors = self.canvas.sample(x * METER_PX, ys * METER_PX)
        moved = ((x != old_x) | (ys != old_ys)) & self.pen_on
        if moved.any():
            self.canvas.draw_lines(x[moved] * METER_PX, ys[moved] * METER_PX,
                                   old_x[moved] * METER_PX, old_ys[moved] * METER_PX,
                                   self.pen_rgb[moved], self.pen_width[moved])
        self._poses = poses
        self._colors = colors
        self._sampled_version = self.canvas.version if not moved.any() else -1
        # Still active while any turtle has a velocity (the timeout must still fire) or
        # something queued a teleport in the meantime.
        self.active = bool((self.vx != 0.0).any() or (self.vy != 0.0).any()
                           or (self.w != 0.0).any() or hit.any())
        return StepResult(tuple(self.names), poses, colors, wall_hits)
