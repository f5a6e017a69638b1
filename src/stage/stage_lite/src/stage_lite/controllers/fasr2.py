"""Stage's `fasr2` (examples/ctrl/fasr2.cc), fasr2.world's foraging robots: each works on a
task (a `<colour>_source` and its `<colour>_sink`, one per word after the name in `ctrl
"fasr2 red green ..."`), carries a flag from the source to the sink along a path the A*
planner (_astar.py) finds over a 32 x 32 grid of the world's `cave` model, and goes to the
`fuel_zone` to dock at a charger (a fiducial of id 2) when its power pack runs low.

Rule for rule as Stage's:
- the first robot's Init reads the tasks and calls srandom (Stage: srandom(time(NULL)); here
  the run's number or the world's seed, or 1 unseeded: World.clock_seed); each robot then
  picks its task with random() % tasks, takes the source's colour, subscribes its laser
  (`ranger:1`) and itself, and reads everything in its position update; its sonar
  (`ranger:0`) and fiducial finder (its first unused `fiducial`) are subscribed only while
  it needs them;
- the grid (made once): `cave` rasterized 32 x 32 over its size, an empty cell costs 1, a
  cell an outline passes 9 (blocked); a plan from the robot's cell to its goal's cell is
  kept for that pair of cells and shared by all robots; its nodes are the path's cell
  centres valued by their steps to the goal;
- the good direction: toward the node of least value within 5 m, plus 0.25 rad (the robots
  keep left: two lanes); none in range (or no nodes): no advice;
- at each position update: the nearest charger seen (fiducial on), then at the source
  (closer than half its width): start waiting (in whole seconds of sim time; a start at
  second 0 never counts) with no flag, while waiting leave with probability 0.0005 per
  update (drand48; forced to recharge, and nothing else this update), take a flag (with
  fewer than the payload, 1), and head for the sink once full; at the sink: give a flag
  (coloured green), and head back to the source when empty; then the mode:
- WORK: avoid obstacles as fasr does, else (hungry: the goal is the fuel zone) replan when
  there is no plan, it gives no advice or the goal moved more than 0.5 m since the last plan
  (the heading then stays 0, or the old plan's advice), when hungry switch the finder on
  and, seeing a charger, DOCK; turn by the heading error and cruise at 0.4 m/s;
- DOCK: toward the charger, aligned with its heading (turn rate: bearing - 2 x (pi -
  (bearing - heading)), normalized); beyond 0.5 m avoid or cruise, else creep at 0.02 m/s,
  stop within 0.08 m (laser off, remember the heading), back off at 0.01 m/s when stalled;
  no charger: stop, finder off, WORK; full (above 95 %): UNDOCK with all sensors on;
- UNDOCK: closer than 0.2 m to the charger, back off at 0.02 m/s unless a back sonar (10 to
  13) reads under 0.2 m; then turn at 0.3 rad/s to face away from the docked heading
  (within 0.05 rad), and WORK: to the source of a new random task without a flag, else to
  the sink, finder and sonar off;
- hungry below 20 % (or after leaving a source), full above 95 %.
Stage's statics (tasks, grid, plans) are the process's; here they are the world's. Where
Stage loops forever (hungry with a plan that never gives advice) this raises instead.
Distances are the C library's hypot, as Stage's. The commonest update (working, away from
the goal, not hungry, avoiding or following the plan) runs for many robots in one kernel
(_fasr2_batch.py), the same to the bit.
"""
import math
import weakref

from numpy import hypot as c_hypot  # math.hypot differs from it in the last bit at times

from stage_lite.model.stage_api import Pose, normalize

from ._avoid import avoid_step
from ._dock import MODE_DOCK, MODE_UNDOCK, MODE_WORK, approach, run_mode, start_working
from ._fasr2_batch import Fasr2Batch
from ._fasr2_plans import ADVICE_RANGE, LANE_BIAS, Shared, reach

CRUISE_SPEED = 0.4        # m/s
AVOID_SPEED = 0.05        # m/s
AVOID_TURN = 0.5          # rad/s
MIN_FRONT_DISTANCE = 0.7  # m
STOP_DISTANCE = 0.5       # m
AVOID_DURATION = 10       # updates, at least
PAYLOAD = 1               # flags carried at most
FUEL_ZONE = 'fuel_zone'
REPLAN_MOVE = 0.5         # m the goal may move before a replan
LEAVE_CHANCE = 0.0005     # per update while waiting at a source
CHARGER_ID = 2
HUNGRY = 0.2
FULL = 0.95
BACK_OFF_DISTANCE = 0.2   # m
BACK_OFF_SPEED = -0.02    # m/s
UNDOCK_TURN = 0.3         # rad/s
UNDOCK_HEADING = 0.05     # rad
WAIT_DISTANCE = 0.2       # m behind
BACK_SONARS = range(10, 14)
DELIVERED_COLOR = (0.0, 1.0, 0.0, 1.0)


_worlds = weakref.WeakKeyDictionary()     # WorldApi -> Shared


def init(model, args):
    if model.type != 'position':
        raise TypeError('fasr2 drives a position model, not a %s' % model.type)
    world = model.get_world()
    shared = _worlds.get(world)
    if shared is None:
        shared = _worlds[world] = Shared(world, args.words()[1:])
    fuel = world.get_model(FUEL_ZONE)
    if fuel is None:
        raise LookupError('fasr2 needs a model named "%s" in the world' % FUEL_ZONE)
    return Robot(model, fuel, shared)


class Robot:
    """One robot's state: its task, goal, plan, mode, avoid count and charger."""

    def __init__(self, pos, fuel_zone, shared):
        self.pos = pos
        self.shared = shared
        self.laser = pos.get_child('ranger:1')
        self.sonar = pos.get_child('ranger:0')
        self.finder = pos.get_unused_model_of_type('fiducial')
        for what, m in (('ranger:1 (the laser fasr2 reads)', self.laser),
                        ('ranger:0 (the sonar fasr2 reads)', self.sonar),
                        ('unused fiducial finder', self.finder)):
            if m is None:
                raise LookupError('%s has no %s' % (pos.token, what))
        if not self.laser.sensors:
            raise LookupError('%s\'s ranger:1 has no sensor (fasr2 reads its first)'
                              % pos.token)
        self.scan = self.laser.sensors[0]
        if len(self.sonar.sensors) <= BACK_SONARS[-1]:
            raise LookupError('%s\'s sonar has %d sensors: fasr2 reads sensors %d to %d'
                              % (pos.token, len(self.sonar.sensors), BACK_SONARS[0],
                                 BACK_SONARS[-1]))
        self.pack = pos.find_power_pack()
        if self.pack is None:
            raise LookupError('%s has no power pack (fasr2 reads its charge)' % pos.token)
        self.wait_started_at = -1
        self.task = pos.world.random() % len(shared.tasks)
        self.fuel_zone = fuel_zone
        start_working(self)
        self.docked_angle = 0.0
        self.goal = shared.tasks[self.task].source
        self.cached_goal_pose = Pose()
        self.plan = None
        self.subscribed = {'fiducial': False, 'laser': False, 'sonar': False}
        self.force_recharge = False
        pos.set_color(self.goal.color)
        shared.tasks[self.task].participants += 1
        self.enable('laser', True)
        pos.add_callback('update', self.update)
        pos.subscribe()

    # ---- sensors on and off --------------------------------------------------------------
    def enable(self, which, on):
        if on != self.subscribed[which]:
            self.subscribed[which] = on
            sensor = {'fiducial': self.finder, 'laser': self.laser, 'sonar': self.sonar}[which]
            sensor.subscribe() if on else sensor.unsubscribe()

    # ---- the power pack ------------------------------------------------------------------
    def hungry(self):
        return self.force_recharge or self.pack.proportion_remaining() < HUNGRY

    def full(self):
        return self.pack.proportion_remaining() > FULL

    # ---- plans and goals -----------------------------------------------------------------
    def replan(self, goal_pose):
        shared = self.shared
        self.plan = shared.plan(shared.cell(self.pos.get_pose()), shared.cell(goal_pose))

    def set_goal(self, goal):
        if goal is not self.goal:
            self.goal = goal
            self.replan(goal.get_pose())
            self.pos.set_color(goal.color)

    def set_task(self, task):
        self.task = task
        self.shared.tasks[task].participants += 1

    # ---- the update ----------------------------------------------------------------------
    def update(self, pos, _):
        pose = pos.get_pose()
        self.charger_ahoy = False
        if self.subscribed['fiducial']:
            self.see_charger()
        task = self.shared.tasks[self.task]
        if self.goal is task.source:
            if self.at_source(pos, pose):
                return False
        elif self.goal is task.sink:
            self.at_sink(pos, pose)
        run_mode(self)
        return False

    def see_charger(self):
        closest = None
        for f in self.finder.fiducials:
            if f.id == CHARGER_ID and (closest is None or f.range < closest.range):
                closest = f
        if closest is not None:
            self.charger_ahoy = True
            self.charger_bearing = closest.bearing
            self.charger_range = closest.range
            self.charger_heading = closest.geom[3]

    def at_source(self, pos, pose):
        """The source's rules; True when the robot gives up its task (nothing else this
        update)."""
        source = self.goal
        there = source.get_pose()
        near = c_hypot(there.x - pose.x, there.y - pose.y) < reach(source)
        if near and self.wait_started_at < 0 and pos.get_flag_count() == 0:
            self.wait_started_at = int(pos.world.sim_time_now() / 1e6)
        if self.wait_started_at > 0 and pos.world.drand48() < LEAVE_CHANCE:
            self.force_recharge = True
            self.shared.tasks[self.task].participants -= 1
            self.wait_started_at = -1
            return True
        if near and pos.get_flag_count() < PAYLOAD:
            pos.push_flag(source.pop_flag())
            if pos.get_flag_count() == 1 and self.wait_started_at > 0:
                self.wait_started_at = -1
            if pos.get_flag_count() == PAYLOAD:
                self.set_goal(self.shared.tasks[self.task].sink)
        return False

    def at_sink(self, pos, pose):
        sink = self.goal
        there = sink.get_pose()
        if c_hypot(there.x - pose.x, there.y - pose.y) < reach(sink) \
                and pos.get_flag_count() > 0:
            flag = pos.pop_flag()
            flag.color = DELIVERED_COLOR
            sink.push_flag(flag)
            if pos.get_flag_count() == 0:
                self.set_goal(self.shared.tasks[self.task].source)

    # ---- the modes -----------------------------------------------------------------------
    def obstacle_avoid(self):
        busy, self.avoid_count = avoid_step(
            self.pos, self.scan.ranges, self.avoid_count, MIN_FRONT_DISTANCE,
            STOP_DISTANCE, AVOID_SPEED, AVOID_TURN, AVOID_DURATION)
        return busy

    def work(self):
        if self.obstacle_avoid():
            return
        pos = self.pos
        if self.hungry():
            self.set_goal(self.fuel_zone)
        pose = pos.get_pose()
        a_goal = 0.0
        advice = None if self.plan is None else self.plan.good_direction(pose.x, pose.y)
        if advice is not None:
            a_goal = advice
        goal_pose = self.goal.get_pose()
        moved = c_hypot(goal_pose.x - self.cached_goal_pose.x,
                        goal_pose.y - self.cached_goal_pose.y)
        if advice is None or moved > REPLAN_MOVE:
            self.replan(goal_pose)
            self.cached_goal_pose = goal_pose
        if self.hungry():
            self.enable('fiducial', True)
            advice = self.plan.good_direction(pose.x, pose.y)
            if advice is None:
                raise RuntimeError('%s is hungry and its plan gives no advice: Stage\'s '
                                   'fasr2 would replan here forever' % pos.token)
            a_goal = advice
            if self.charger_ahoy:
                self.mode = MODE_DOCK
        pos.set_turn_speed(normalize(a_goal - pose.a))
        pos.set_x_speed(CRUISE_SPEED)

    def dock(self):
        pos = self.pos
        if self.charger_ahoy:
            orient = normalize(math.pi - (self.charger_bearing - self.charger_heading))
            a_goal = normalize(self.charger_bearing - 2.0 * orient)
            if approach(pos, self.charger_range, a_goal, self.obstacle_avoid):
                self.docked_angle = pos.get_pose().a
                self.enable('laser', False)
        else:
            pos.stop()
            self.enable('fiducial', False)
            self.mode = MODE_WORK
        if self.full():
            self.mode = MODE_UNDOCK
            self.enable('sonar', True)
            self.enable('laser', True)
            self.enable('fiducial', True)
            self.force_recharge = False

    def undock(self):
        pos = self.pos
        if self.charger_range < BACK_OFF_DISTANCE:
            pos.set_x_speed(BACK_OFF_SPEED)
            sensors = self.sonar.sensors
            for s in BACK_SONARS:
                ranges = sensors[s].ranges
                if ranges is None or len(ranges) < 1 or ranges[0] < WAIT_DISTANCE:
                    pos.set_x_speed(0.0)
                    return
        else:
            heading_error = normalize(pos.get_pose().a - (self.docked_angle + math.pi))
            if abs(heading_error) > UNDOCK_HEADING:
                pos.set_x_speed(0.0)
                pos.set_turn_speed(UNDOCK_TURN * (-1.0 if -heading_error < 0 else 1.0))
            else:
                self.mode = MODE_WORK
                tasks = self.shared.tasks
                if pos.get_flag_count() == 0:
                    self.set_task(pos.world.random() % len(tasks))
                    self.set_goal(tasks[self.task].source)
                else:
                    self.set_goal(tasks[self.task].sink)
                self.enable('fiducial', False)
                self.enable('sonar', False)


# the working robots' updates in one kernel (_fasr2_batch.py), the rest as above
Robot.update.batch = Fasr2Batch(dict(
    work=MODE_WORK, front=MIN_FRONT_DISTANCE, stop=STOP_DISTANCE,
    avoid_speed=AVOID_SPEED, avoid_turn=AVOID_TURN, avoid_duration=AVOID_DURATION,
    cruise=CRUISE_SPEED, replan_move=REPLAN_MOVE,
    advice_range=ADVICE_RANGE, lane_bias=LANE_BIAS))
