"""Stage's `fasr` (examples/ctrl/fasr.cc), fasr.world's foraging robots: fetch a flag at the
world's "source" (near (-7, -7)), carry it to its "sink" (near (7, 7)), and dock at a
charging station (a fiducial of id 2) when the power pack runs low.

Rule for rule as Stage's:
- the laser is the robot's `ranger:1`, the fiducial finder its first unused `fiducial`;
  the robot, the laser and the finder are subscribed, each with its update callback;
- the laser's update drives, by mode: WORK (avoid obstacles, else cruise at 0.4 m/s and
  turn toward the heading the grid cell of the pose gives: the HAVE table carrying a flag,
  NEED without, REFUEL when hungry, and DOCK on seeing a charger while hungry), DOCK (steer
  to the charger: at 0.4 m/s beyond 0.5 m, then creep at 0.02 m/s, stop within 0.08 m,
  back off at 0.01 m/s when stalled; no charger seen: stop and back to WORK; full: UNDOCK),
  UNDOCK (back off at 0.05 m/s until the charger is 0.3 m away, then WORK);
- obstacle avoidance: something within 0.7 m in the middle half of the beams, or within
  0.5 m anywhere: creep at 0.05 m/s (stop if within 0.5 m) and turn 0.5 rad/s away from the
  nearer side for random() % 10 + 10 laser updates (drawn from the world's stream);
- hungry below 25 % of the pack, full above 95 %;
- at each position update: with fewer flags than the payload (1) within 2 m of (-7, -7),
  after 20 updates there it takes the source's flag (if it has one), and within 1 m of
  (7, 7), every 21st update there, gives the sink its flag (if it carries one);
- at each finder update: the first reading with id 2 is the charger (range, bearing, his
  heading); none: no charger in sight.
The cell of a pose is ((x + 8) / 4, (y + 8) / 4), truncated toward zero, held to 0..3.
A working robot's laser update that is not hungry runs in one kernel with the others', and
a finder's update that saw nothing beside them, and the position updates away from the
source and the sink in another (_fasr_batch.py), the same to the bit.
"""
import math

from numpy import hypot as c_hypot  # Stage's (the C library's); math.hypot differs at times

from stage_lite.model.stage_api import normalize

from ._avoid import AVOID_PART, avoid_step, beam_rule
from ._dock import MODE_DOCK, MODE_UNDOCK, MODE_WORK, approach, run_mode, start_working
from ._fasr_batch import FasrBatch, FasrPositionBatch

CRUISE_SPEED = 0.4        # m/s
AVOID_SPEED = 0.05        # m/s
AVOID_TURN = 0.5          # rad/s
MIN_FRONT_DISTANCE = 0.7  # m
STOP_DISTANCE = 0.5       # m
AVOID_DURATION = 10       # laser updates, at least
WORK_DURATION = 20        # position updates at the source or the sink before a transfer
PAYLOAD = 1               # flags carried at most
SOURCE_XY = (-7.0, -7.0)
SOURCE_RADIUS = 2.0       # m
SINK_XY = (7.0, 7.0)
SINK_RADIUS = 1.0         # m
CHARGER_ID = 2            # the charging stations' fiducial_return
HUNGRY = 0.25             # of the pack's capacity
FULL = 0.95
UNDOCK_DISTANCE = 0.3     # m
UNDOCK_SPEED = -0.05      # m/s
CELL_ORIGIN = 8           # m: the tables' cells count from (-8, -8)
CELL_SIZE = 4             # m
CELLS = 4                 # a side

# Headings (degrees) per grid cell [y][x] of the 16 m x 16 m cave, x and y from -8 m in 4 m
# cells: carrying a flag, looking for one, looking for a charger.
HAVE = ((90, 180, 180, 180),
        (90, -90, 180, 90),
        (90, 90, 180, 90),
        (0, 45, 0, 0))
NEED = ((-120, -180, 180, 180),
        (-90, -120, 180, 90),
        (-90, -90, 180, 180),
        (-90, -180, -90, -90))
REFUEL = ((0, 0, 45, 120),
          (0, -90, -60, -160),
          (-90, -90, 180, 180),
          (-90, -180, -90, -90))



def init(model, args):
    if model.type != 'position':
        raise TypeError('fasr drives a position model, not a %s' % model.type)
    world = model.get_world()
    Forager(model, world.get_model('source'), world.get_model('sink'))


def cell(x, y):
    """The table cell (column, row) of a pose: Stage's int((v + 8) / 4), held to 0..3."""
    return (min(max(int((x + CELL_ORIGIN) / CELL_SIZE), 0), CELLS - 1),
            min(max(int((y + CELL_ORIGIN) / CELL_SIZE), 0), CELLS - 1))


def heading_goal(x, y, carrying, hungry):
    """The heading (rad) the tables give at (x, y)."""
    col, row = cell(x, y)
    table = REFUEL if hungry else (HAVE if carrying else NEED)
    return math.radians(table[row][col])


def scan_rule(scan):
    """(obstruction, stop, nearest on the left, nearest on the right) of a laser scan, by
    fasr's beam rule: the middle half is n/4 < i < n - n/4, the left half i > n/2."""
    return beam_rule(scan, AVOID_PART, MIN_FRONT_DISTANCE, STOP_DISTANCE)


class Forager:
    """One robot's state: its mode, the avoid count, the work counters and the charger."""

    def __init__(self, position, source, sink):
        self.pos = position
        self.laser = position.get_child('ranger:1')
        self.finder = position.get_unused_model_of_type('fiducial')
        if self.laser is None:
            raise LookupError('%s has no ranger:1 (the laser fasr reads)' % position.token)
        for what, m in (('source', source), ('sink', sink)):
            if m is None:
                raise LookupError('fasr needs a model named "%s" in the world' % what)
        if self.finder is None:
            raise LookupError('%s carries no unused fiducial finder' % position.token)
        self.source = source
        self.sink = sink
        self.pack = position.find_power_pack()  # a model's pack is made with it: found once
        start_working(self)
        self.work_get = 0
        self.work_put = 0
        self.at_dest = False
        position.add_callback('update', self.position_update)
        position.subscribe()
        self.laser.add_callback('update', self.laser_update)
        self.laser.subscribe()
        self.finder.add_callback('update', self.fiducial_update)
        self.finder.subscribe()

    # ---- the power pack ------------------------------------------------------------------
    def hungry(self):
        return self.pack.proportion_remaining() < HUNGRY

    def full(self):
        return self.pack.proportion_remaining() > FULL

    # ---- the modes -----------------------------------------------------------------------
    def laser_update(self, laser, _):
        run_mode(self)
        return False

    def dock(self):
        pos = self.pos
        if self.charger_ahoy:
            approach(pos, self.charger_range, normalize(self.charger_bearing),
                     self.obstacle_avoid)
        else:
            pos.stop()
            self.mode = MODE_WORK
        if self.full():
            self.mode = MODE_UNDOCK

    def undock(self):
        self.pos.set_x_speed(UNDOCK_SPEED if self.charger_range < UNDOCK_DISTANCE else 0.0)
        if self.charger_range > UNDOCK_DISTANCE:
            self.mode = MODE_WORK

    def work(self):
        if self.obstacle_avoid():
            return
        pos = self.pos
        pos.set_x_speed(CRUISE_SPEED)
        pose = pos.get_pose()
        hungry = self.hungry()
        a_goal = heading_goal(pose.x, pose.y, pos.get_flag_count() > 0, hungry)
        if hungry and self.charger_ahoy:
            self.mode = MODE_DOCK
        pos.set_turn_speed(normalize(a_goal - pose.a))

    def obstacle_avoid(self):
        """True while avoiding (speed and turn set here)."""
        busy, self.avoid_count = avoid_step(
            self.pos, self.laser.sensors[0].ranges, self.avoid_count, MIN_FRONT_DISTANCE,
            STOP_DISTANCE, AVOID_SPEED, AVOID_TURN, AVOID_DURATION)
        return busy

    # ---- the other callbacks -------------------------------------------------------------
    def position_update(self, pos, _):
        pose = pos.get_pose()
        if pos.get_flag_count() < PAYLOAD and \
                c_hypot(SOURCE_XY[0] - pose.x, SOURCE_XY[1] - pose.y) < SOURCE_RADIUS:
            self.work_get += 1
            if self.work_get > WORK_DURATION:
                pos.push_flag(self.source.pop_flag())
                self.work_get = 0
        self.at_dest = False
        if c_hypot(SINK_XY[0] - pose.x, SINK_XY[1] - pose.y) < SINK_RADIUS:
            self.at_dest = True
            self.work_put += 1
            if self.work_put > WORK_DURATION:
                self.sink.push_flag(pos.pop_flag())
                self.work_put = 0
        return False

    def fiducial_update(self, finder, _):
        self.charger_ahoy = False
        for seen in finder.fiducials:
            if seen.id == CHARGER_ID:
                self.charger_ahoy = True
                self.charger_bearing = seen.bearing
                self.charger_range = seen.range
                self.charger_heading = seen.geom[3]
                break
        return False


# the working robots' laser updates in one kernel and the finders' that saw nothing in the
# same batch (_fasr_batch.py), the rest as above
Forager.laser_update.batch = Forager.fiducial_update.batch = FasrBatch(dict(
    work=MODE_WORK, front=MIN_FRONT_DISTANCE, stop=STOP_DISTANCE, avoid_speed=AVOID_SPEED,
    avoid_turn=AVOID_TURN, avoid_duration=AVOID_DURATION, cruise=CRUISE_SPEED, need=NEED,
    have=HAVE, cell_origin=CELL_ORIGIN, cell_size=CELL_SIZE, cells=CELLS,
    finder_update=Forager.fiducial_update))
# the position updates away from the source and the sink in one kernel (_fasr_batch.py)
Forager.position_update.batch = FasrPositionBatch(dict(
    source=SOURCE_XY, source_radius=SOURCE_RADIUS, sink=SINK_XY, sink_radius=SINK_RADIUS))
