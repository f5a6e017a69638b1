"""Stage's fasr2 (controllers/fasr2.py), rule by rule, on the workspace's own
test/worlds/fasr2_small.world: a 16 m cave split by a wall at x = 0 (a gap at its north
end), one task (red_source west of the wall, red_sink east of it), a fuel zone with a
charger, three robots (walker, carrier, and hungry at 15 % of its pack)."""
import math
import os

import pytest
from stage_lite.controllers import _fasr2_plans as plans
from stage_lite.controllers import fasr2
from stage_lite.controllers._dock import DOCK_CLOSE
from stage_lite.model.stage_api import Flag, normalize
from stage_lite.model.world import WorldError, load_world

WORLD = os.path.join(os.path.dirname(__file__), '..', 'worlds', 'fasr2_small.world')
CELL = 0.5     # the small cave's 16 m over 32 cells


@pytest.fixture
def world():
    return load_world(WORLD, seed=7, stageros=False)


def named(w, name):
    return next(m for m in w.models if m.token == name)


def robot_of(w, name):
    """The controller's Robot behind a robot's update callback."""
    model = named(w, name)
    for callback, _, _ in w.scheduler.callbacks[(model, 'update')]:
        found = getattr(callback.function, '__self__', None)   # stage_api.ApiCallback
        if isinstance(found, fasr2.Robot):
            return found
    raise LookupError(name)


def shared_of(w):
    return fasr2._worlds[w.handle(named(w, 'walker')).world]


def step_until(w, done, limit):
    for k in range(limit):
        w.step()
        if done():
            return k + 1
    raise AssertionError('not within %d steps' % limit)


# ---- the grid and the plans ------------------------------------------------------------------
def test_cells_are_the_maps_32nds_from_its_corner_and_nodes_their_centres():
    cells = [plans.meters_to_cell(m, 100.0, 32) for m in (-50.0, -46.876, -46.875, 0.0, 49.99)]
    assert cells == \
        [0, 0, 1, 16, 31]
    assert plans.cell_to_meters(0, 100.0, 32) == -50.0 + 100.0 / 64
    assert plans.cell_to_meters(16, 16.0, 32) == 0.25


def test_the_grid_is_the_caves_outline_raster_free_1_blocked_9(world):
    costs = shared_of(world).costs.reshape(32, 32)
    assert set(costs.ravel().tolist()) == {1, plans.BLOCKED}
    # the frame, and the wall at x = 0 from the south edge up to y = 3 (row 22), not above
    assert (costs[0] == 9).all() and (costs[31] == 9).all() and (costs[:, 0] == 9).all()
    assert (costs[1:22, 15:17] == 9).all() and (costs[23:31, 1:31] == 1).all()
    assert (costs[1:22, 1:15] == 1).all() and (costs[1:22, 17:31] == 1).all()


def test_a_plan_goes_round_the_wall_and_is_kept_for_its_pair_of_cells(world):
    shared = shared_of(world)
    start, goal = (6, 6), (26, 6)            # the source's and the sink's cells
    plan = shared.plan(start, goal)
    assert shared.plan(start, goal) is plan and shared.misses == 1
    centre = [plans.cell_to_meters(c, 16.0, 32) for c in range(32)]
    assert (plan.xs[0], plan.ys[0]) == (centre[26], centre[6])     # the goal first: value 0
    assert (plan.xs[-1], plan.ys[-1]) == (centre[6], centre[6])
    assert plan.ys.max() > 3.0                                # over the wall's end
    steps = abs(plan.xs[1:] - plan.xs[:-1]) + abs(plan.ys[1:] - plan.ys[:-1])
    assert (steps == CELL).all()                              # cell by cell


def test_a_failed_plan_gives_no_advice():
    empty = plans.Plan([], [])
    assert empty.good_direction(0.0, 0.0) is None


def test_the_good_direction_is_the_least_valued_node_within_5_m_plus_a_quarter_radian():
    # values by index: the goal (0) is 6 m away, node 1 at 4.9 m, node 2 nearer still
    plan = plans.Plan([6.0, 0.0, 1.0], [0.0, 4.9, 0.0])
    assert plan.good_direction(0.0, 0.0) == pytest.approx(math.pi / 2 + 0.25)
    assert plans.Plan([6.0, 0.0], [0.0, 5.0]).good_direction(0.0, 0.0) is None
    assert plans.Plan([-1.0], [-1e-9]).good_direction(0.0, 0.0) == normalize(
        math.atan2(-1e-9, -1.0) + 0.25)                        # wrapped round


# ---- starting up -----------------------------------------------------------------------------
def test_each_robot_takes_its_tasks_source_colour_and_reads_its_laser_only(world):
    shared = shared_of(world)
    assert [(t.source.token, t.sink.token) for t in shared.tasks] == [('red_source', 'red_sink')]
    assert shared.tasks[0].participants == 3
    source = named(world, 'red_source')
    for name in ('walker', 'carrier'):
        robot = robot_of(world, name)
        assert robot.goal.token == 'red_source' and named(world, name).color == source.color
        assert robot.subscribed == {'fiducial': False, 'laser': True, 'sonar': False}


def test_the_first_update_heads_east_then_follows_the_plan(world):
    carrier = robot_of(world, 'carrier')
    world.step()
    assert carrier.plan is not None
    a = carrier.pos.get_pose().a
    assert carrier.pos.get_goal().a == normalize(0.0 - a)      # no plan yet: heading 0
    world.step()
    pose = carrier.pos.get_pose()
    advice = carrier.plan.good_direction(pose.x, pose.y)
    assert carrier.pos.get_goal().a == normalize(advice - pose.a)
    assert carrier.pos.get_goal().x == fasr2.CRUISE_SPEED


# ---- flags -----------------------------------------------------------------------------------
def test_at_the_source_it_takes_one_flag_and_heads_for_the_sink(world):
    walker = robot_of(world, 'walker')
    source, sink = named(world, 'red_source'), named(world, 'red_sink')
    step_until(world, lambda: walker.pos.get_flag_count() == 1, 300)
    pose = walker.pos.get_pose()
    assert math.hypot(pose.x + 5, pose.y + 5) < 1.0           # within half the zone's width
    assert walker.goal.token == 'red_sink' and named(world, 'walker').color == sink.color
    assert walker.wait_started_at == -1                       # it waited, and stopped
    for _ in range(20):
        world.step()
    assert walker.pos.get_flag_count() == fasr2.PAYLOAD and len(source.flags) == 10


def test_at_the_sink_it_gives_its_flag_green_and_heads_back(world):
    carrier = robot_of(world, 'carrier')
    sink = named(world, 'red_sink')
    carrier.pos.push_flag(Flag())
    carrier.set_goal(shared_of(world).tasks[0].sink)
    step_until(world, lambda: len(sink.flags) == 1, 300)
    assert sink.flags[0].color == fasr2.DELIVERED_COLOR
    assert carrier.pos.get_flag_count() == 0 and carrier.goal.token == 'red_source'


def test_waiting_at_the_source_it_may_give_up_and_go_to_recharge(world, monkeypatch):
    walker = robot_of(world, 'walker')
    api = walker.pos.world
    draws = iter([0.0])                    # the first draw below 0.0005, then none
    monkeypatch.setattr(api, 'drand48', lambda: next(draws, 1.0))
    step_until(world, lambda: walker.force_recharge, 300)
    assert walker.wait_started_at == -1 and walker.pos.get_flag_count() == 0
    assert shared_of(world).tasks[0].participants == 2
    # still on the source: it waits again, takes a flag, and, forced hungry, heads for fuel
    step_until(world, lambda: walker.goal.token == 'fuel_zone', 50)
    assert walker.pos.get_flag_count() == 1 and walker.subscribed['fiducial']


def test_a_wait_begun_in_second_0_never_counts(world, monkeypatch):
    walker = robot_of(world, 'walker')
    walker.pos._model.pose = (-5.0, -5.0, 0.0, 0.0)           # on the source from the start
    calls = []
    monkeypatch.setattr(walker.pos.world, 'drand48', lambda: calls.append(1) or 1.0)
    world.step()
    assert walker.wait_started_at == 0 and walker.pos.get_flag_count() == 1
    for _ in range(30):
        world.step()
    assert walker.wait_started_at == 0 and not calls          # no draw: never waiting


# ---- charging --------------------------------------------------------------------------------
def test_a_hungry_robot_docks_charges_undocks_and_takes_a_new_task(world):
    hungry = robot_of(world, 'hungry')
    pack = hungry.pos.find_power_pack()
    world.step()
    assert hungry.goal.token == 'fuel_zone'                   # hungry from its first update
    modes = [hungry.mode]
    for _ in range(1500):
        world.step()
        if hungry.mode == modes[-1]:
            continue
        modes.append(hungry.mode)
        if hungry.mode == fasr2.MODE_UNDOCK:
            assert pack.proportion_remaining() > fasr2.FULL and not hungry.force_recharge
            assert hungry.subscribed == {'fiducial': True, 'laser': True, 'sonar': True}
        elif hungry.mode == fasr2.MODE_WORK:
            break
    assert modes == [fasr2.MODE_WORK, fasr2.MODE_DOCK, fasr2.MODE_UNDOCK, fasr2.MODE_WORK]
    assert hungry.charger_range >= fasr2.BACK_OFF_DISTANCE
    error = normalize(hungry.pos.get_pose().a - (hungry.docked_angle + math.pi))
    assert abs(error) <= fasr2.UNDOCK_HEADING
    assert hungry.goal.token == 'red_source'                  # no flag: a task's source
    assert hungry.subscribed == {'fiducial': False, 'laser': True, 'sonar': False}


def test_docked_the_laser_is_off(world):
    hungry = robot_of(world, 'hungry')
    step_until(world, lambda: hungry.charger_ahoy and hungry.charger_range < DOCK_CLOSE,
               800)
    assert not hungry.subscribed['laser'] and hungry.mode == fasr2.MODE_DOCK
    assert hungry.docked_angle == hungry.pos.get_pose().a


# ---- what can go wrong -----------------------------------------------------------------------
def small_world():
    with open(WORLD) as f:
        return f.read()


def variant(tmp_path, old, new):
    text = small_world()
    assert old in text
    path = tmp_path / 'fasr2.world'
    path.write_text(text.replace(old, new))
    line = next(i for i, t in enumerate(text.replace(old, new).splitlines(), 1)
                if 'ctrl "fasr2' in t)
    return str(path), line


@pytest.mark.parametrize('old, new, what', [
    ('ctrl "fasr2 red"', 'ctrl "fasr2"', 'fasr2 needs at least one task colour'),
    ('ctrl "fasr2 red"', 'ctrl "fasr2 red blue"',
     'fasr2\'s task "blue" needs a model named "blue_source"'),
    ('name "cave"', 'name "walls"', 'fasr2 plans on a model named "cave"'),
    ('name "fuel_zone"', 'name "fuel"', 'fasr2 needs a model named "fuel_zone"'),
    ('sonar_ring( ) laser', 'laser', 'has no ranger:1 (the laser fasr2 reads)'),
    ('kjoules 400 kjoules_capacity 400 ', '', 'has no power pack'),
    ('define laser ranger ( sensor( range [ 0 2 ] fov 180 samples 32 ) )',
     'define laser ranger ( )', "ranger:1 has no sensor (fasr2 reads its first)"),
    ('sonar_ring( ) laser( pose [ 0 0 -0.1 0 ] )', 'sonar_ring( )',
     'has no ranger:1 (the laser fasr2 reads)'),
    ('  bump( fiducial( range_max_id 9 range_max 9 fov 180 pose [ 0 0 -0.05 0 ] ) )\n', '',
     'has no unused fiducial finder'),
    ('define forager position', 'define forager model', 'fasr2 drives a position model'),
])
def test_fasr2_without_what_it_needs_is_one_error_on_its_ctrl_line(tmp_path, old, new, what):
    path, line = variant(tmp_path, old, new)
    with pytest.raises(WorldError) as err:
        load_world(path, stageros=False)
    assert str(err.value).startswith('%s:%d:' % (path, line)), err.value
    assert what in str(err.value)


def test_a_sonar_of_fewer_than_14_sensors_is_refused(tmp_path):
    text = small_world()
    cut = text.index('  sensor( pose [ -0.250 -0.025')
    end = text.index(')\ndefine laser')
    path = tmp_path / 'fasr2.world'
    path.write_text(text[:cut] + text[end:])
    with pytest.raises(WorldError, match='sonar has 11 sensors: fasr2 reads sensors 10 to 13'):
        load_world(str(path), stageros=False)

