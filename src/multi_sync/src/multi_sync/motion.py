"""Driving a robot forward safely: bumper, teammates' positions, team layout (no rospy).

Frame: the simulator's world, metres, theta in radians counter-clockwise from +x. On turtlesim
the origin is the bottom-left corner of its square world (x right, y up); on Stage it is
Stage's world origin. The bumper takes the free distance ahead from the robot's sensor:
turtlesim's square (distance_to_wall) or Stage's laser (multi_sync.laser_ahead).
"""
import math
from dataclasses import dataclass

# turtlesim's square world and its middle, where turtlesim's first turtle starts.
from course_common.arena import CENTRE_M, WORLD_SIZE_M
from course_common.finite import is_finite_number
from course_common.robot_ids import MAX_ROBOTS, valid_robot_id

# The lesson's robots stand 2 m apart in a 2x2 square; the grid keeps that spacing.
GRID_STEP_M = 2.0
# The two simulators a robot drives on (its first pose names it: multi_sync.robot_sensors).
TURTLESIM = 'turtlesim'
STAGE = 'Stage'


def _check_finite(**values):
    for name, value in values.items():
        if not is_finite_number(value):
            raise ValueError('%s must be a finite number, got %r' % (name, value))


def distance_to_wall(x, y, theta, world_size=WORLD_SIZE_M):
    """Distance in metres from (x, y) to the world's edge, straight along heading theta.

    A point on or beyond an edge it is heading into is 0 m from the wall.
    """
    _check_finite(x=x, y=y, theta=theta, world_size=world_size)
    if world_size <= 0.0:
        raise ValueError('world_size must be positive, got %r' % world_size)
    dx, dy = math.cos(theta), math.sin(theta)
    candidates = []
    # Components below 1e-12 run parallel to that pair of walls: they never reach them.
    if dx > 1e-12:
        candidates.append((world_size - x) / dx)
    elif dx < -1e-12:
        candidates.append(-x / dx)
    if dy > 1e-12:
        candidates.append((world_size - y) / dy)
    elif dy < -1e-12:
        candidates.append(-y / dy)
    return max(0.0, min(candidates))


@dataclass(frozen=True)
class Teammate:
    """The latest known position of one teammate (world frame, m and rad; stamp in s)."""

    robot_id: int
    x: float
    y: float
    theta: float
    stamp_s: float


class TeamPositions:
    """The latest position of every teammate, as heard on the shared positions topic."""

    def __init__(self, own_id):
        if not valid_robot_id(own_id):
            raise ValueError('own_id must be an integer in 0..%d, got %r'
                             % (MAX_ROBOTS - 1, own_id))
        self.own_id = own_id
        self._latest = {}

    def update(self, robot_id, x, y, theta, stamp_s):
        """Store a teammate's position; return False for the robot's own (ignored).

        Raises ValueError for an id outside 0..19 or a non-finite value. The latest message
        wins whatever its stamp: one publisher's messages arrive in order, and a robot
        restarted on the Stage lesson may stamp with another clock than before (a node that
        started before stageros set /use_sim_time keeps wall time, one started after runs on
        sim time), so stamps cannot order two runs of the same robot.
        """
        if not valid_robot_id(robot_id):
            raise ValueError('robot_id must be an integer in 0..%d, got %r'
                             % (MAX_ROBOTS - 1, robot_id))
        _check_finite(x=x, y=y, theta=theta, stamp_s=stamp_s)
        if robot_id == self.own_id:
            return False
        self._latest[robot_id] = Teammate(robot_id, float(x), float(y), float(theta),
                                          float(stamp_s))
        return True

    def teammates(self):
        """The stored teammates, by id."""
        return [self._latest[k] for k in sorted(self._latest)]

    def nearest(self, x, y):
        """(teammate, distance in m) of the nearest teammate to (x, y), or None if none known."""
        _check_finite(x=x, y=y)
        best = None
        for mate in self.teammates():
            d = math.hypot(mate.x - x, mate.y - y)
            if best is None or d < best[1]:
                best = (mate, d)
        return best

    def blocking(self, x, y, theta, min_gap_m):
        """(teammate, distance) of the nearest teammate ahead closer than min_gap_m, or None.

        Ahead means in the half-plane in front of the robot (positive projection on its
        heading): a teammate behind or exactly beside it does not stop it, so two robots
        never block each other and the one in front can always drive away.
        """
        _check_finite(x=x, y=y, theta=theta, min_gap_m=min_gap_m)
        if min_gap_m < 0.0:
            raise ValueError('min_gap_m must be >= 0, got %r' % min_gap_m)
        hx, hy = math.cos(theta), math.sin(theta)
        best = None
        for mate in self.teammates():
            rx, ry = mate.x - x, mate.y - y
            d = math.hypot(rx, ry)
            if d < min_gap_m and rx * hx + ry * hy > 0.0 and (best is None or d < best[1]):
                best = (mate, d)
        return best


@dataclass(frozen=True)
class DriveLimits:
    """How a robot drives: speed (m/s), bumper distance (m), teammate gap (m), world (m).

    stop_distance_m and min_gap_m of 0 turn the bumper and the gap off: the robot drives on
    until the simulator stops it (turtlesim clamps it at the wall, Stage stalls it).
    world_size_m is turtlesim's square, which bounds the bumper distance; None on Stage,
    where the laser measures what is ahead and no square bounds it.
    """

    speed_mps: float = 0.2
    stop_distance_m: float = 0.5
    min_gap_m: float = 1.0
    world_size_m: float = WORLD_SIZE_M

    def __post_init__(self):
        _check_finite(speed_mps=self.speed_mps, stop_distance_m=self.stop_distance_m,
                      min_gap_m=self.min_gap_m)
        if self.world_size_m is not None:
            _check_finite(world_size_m=self.world_size_m)
        if self.speed_mps <= 0.0:
            raise ValueError('speed_mps must be > 0, got %r' % self.speed_mps)
        if self.stop_distance_m < 0.0:
            raise ValueError('stop_distance_m must be >= 0, got %r' % self.stop_distance_m)
        if self.min_gap_m < 0.0:
            raise ValueError('min_gap_m must be >= 0, got %r' % self.min_gap_m)
        if self.world_size_m is not None and not self.stop_distance_m * 2.0 < self.world_size_m:
            raise ValueError('stop_distance_m must be less than half the world (%r m), got %r'
                             % (self.world_size_m, self.stop_distance_m))


@dataclass(frozen=True)
class Decision:
    """The forward speed to command now and why: 'clear', 'wall' or 'teammate' (decide's),
    or 'stale' (move_robot's own: its inputs went silent).

    ahead_m is the free distance ahead the sensor gave (the wall on turtlesim, what the
    laser sees on Stage); for 'teammate', teammate_id and gap_m name the teammate in the way
    and how far it is.
    """

    linear_mps: float
    reason: str
    ahead_m: float
    teammate_id: int = -1
    gap_m: float = math.inf


def decide(x, y, theta, ahead_m, limits, team=None):
    """Forward speed for a robot at (x, y, theta): full speed unless a wall or teammate is near.

    ahead_m is the free distance straight ahead as the robot's sensor measures it (m, inf
    when nothing is in range). The bumper stops the robot once it is at most
    limits.stop_distance_m; with team given, a teammate ahead closer than limits.min_gap_m
    stops it too (it drives on when that teammate has moved away). Either limit at 0 is off.
    """
    if not (is_finite_number(ahead_m) or ahead_m == math.inf) or ahead_m < 0.0:
        raise ValueError('ahead_m must be >= 0 m or inf, got %r' % (ahead_m,))
    if limits.stop_distance_m > 0.0 and ahead_m <= limits.stop_distance_m:
        return Decision(0.0, 'wall', ahead_m)
    if team is not None and limits.min_gap_m > 0.0:
        block = team.blocking(x, y, theta, limits.min_gap_m)
        if block is not None:
            return Decision(0.0, 'teammate', ahead_m, block[0].robot_id, block[1])
    return Decision(limits.speed_mps, 'clear', ahead_m)


def team_layout(team_size):
    """Start poses (x, y, theta) of robots 0..team_size-1, heading +x, all inside the world.

    Robots 0..3 stand as in the lesson's 2x2 group (Stage's (-11.5, 23.5), (-13.5, 23.5),
    (-11.5, 21.5), (-13.5, 21.5), moved so robot 0 is turtlesim's turtle1 in the centre).
    Further robots fill a 4 x 5 grid with the same 2 m spacing, nearest the group first.
    """
    if isinstance(team_size, bool) or not isinstance(team_size, int) \
            or not 1 <= team_size <= MAX_ROBOTS:
        raise ValueError('team_size must be an integer in 1..%d, got %r'
                         % (MAX_ROBOTS, team_size))
    # Columns from the front (+x) back, rows from the top down: x in 1.54..7.54, y in 1.54..9.54.
    xs = [CENTRE_M + GRID_STEP_M * (1 - col) for col in range(4)]
    ys = [CENTRE_M + GRID_STEP_M * (2 - row) for row in range(5)]
    group_x, group_y = CENTRE_M - GRID_STEP_M / 2, CENTRE_M - GRID_STEP_M / 2

    def key(slot):
        sx, sy = slot
        return (round(math.hypot(sx - group_x, sy - group_y), 6), -sy, -sx)

    slots = sorted(((sx, sy) for sx in xs for sy in ys), key=key)
    return [(sx, sy, 0.0) for sx, sy in slots[:team_size]]
