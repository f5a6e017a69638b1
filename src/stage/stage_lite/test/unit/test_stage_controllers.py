"""Stage's controllers: found and started as Stage does, driving as their C++ rules say, and
every way a controller can be wrong reported on the world file's line."""
import math
import os
import sys

import numpy as np
import pytest
from stage_lite.controllers import wander
from stage_lite.controllers._expand import Law, steer
from stage_lite.model.bodies import Block, rasterize
from stage_lite.model.glibc_random import Random
from stage_lite.model.noise import RangerNoise
from stage_lite.model.world import WorldError, load_world

ROOM = '''resolution 0.02
interval_sim 100
define laser ranger ( sensor( range [ 0 8 ] fov 180 samples 37 ) )
model( pose [ 0 0 0 0 ] size [ 10 10 0.5 ] boundary 1 noblocks 1 obstacle_return 1 )
'''


def world_file(tmp_path, body, name='w.world'):
    path = tmp_path / name
    path.write_text(ROOM + body)
    return str(path)


# ---- wander, rule by rule ------------------------------------------------------------------
def test_wander_looks_for_obstructions_in_the_middle_third_only():
    far = np.full(9, 5.0)
    for i, seen in [(3, False), (4, True), (5, True), (6, False)]:   # n/3 < i < n - n/3
        scan = far.copy()
        scan[i] = 0.9
        assert wander.decide(scan)[0] is seen, i


def test_wander_stops_for_anything_within_0_3_m_and_splits_left_from_right():
    scan = np.full(9, 5.0)
    scan[0] = 0.29                       # the rightmost beam
    obstruction, stop, min_left, min_right = wander.decide(scan)
    assert (obstruction, stop, min_left, min_right) == (False, True, 5.0, 0.29)
    scan[:] = 5.0
    scan[5] = 2.0                        # i > n/2: the left half
    assert wander.decide(scan)[2:] == (2.0, 5.0)


class _Position:
    """What wander commands, recorded; its world's random() is a glibc stream."""

    def __init__(self, stream):
        self.speeds = []
        self.world = self
        self._stream = stream

    def random(self):
        return self._stream.random()

    def set_x_speed(self, x):
        self.speeds.append(('x', x))

    def set_turn_speed(self, a):
        self.speeds.append(('a', a))


class _Laser:
    def __init__(self, scan):
        self.sensors = [type('S', (), {'ranges': np.asarray(scan, float)})()]


def test_an_avoidance_lasts_random_mod_10_plus_10_updates_and_keeps_its_side():
    position = _Position(Random())                 # an unseeded process's first random()
    scan = np.full(9, 5.0)
    scan[4] = 0.5                                  # ahead
    scan[2] = 0.8                                  # nearer on the right: turn left
    laser = _Laser(scan)
    robot = wander.Wanderer(position, laser)
    robot.laser_update(laser, None)
    assert position.speeds == [('x', wander.AVOID_SPEED), ('a', wander.AVOID_TURN)]
    assert robot.avoid_count == 1804289383 % 10 + 10 - 1
    laser.sensors[0].ranges[:] = 5.0               # clear now, but the avoidance goes on
    position.speeds.clear()
    robot.laser_update(laser, None)
    assert position.speeds == [('x', wander.AVOID_SPEED)] and robot.avoid_count == 11
    robot.avoid_count = 0
    robot.laser_update(laser, None)
    assert position.speeds[-2:] == [('x', wander.CRUISE_SPEED), ('a', 0.0)]


def test_the_expand_law_steers_along_the_sum_and_drives_only_when_clear():
    headings = [2 * math.pi * k / 12 for k in range(12)]
    law = Law(0.3, 1.0, 0.5, ((0, 0.5), (1, 0.5 / 1.5)))
    commands = []
    position = type('P', (), {'set_speed': lambda self, *v: commands.append(v)})()

    def ranger(first):
        return type('R', (), {'sensors': [type('S', (), {'ranges': [r]})() for r in first]})()
    ranges = [1.0] * 12
    ranges[0], ranges[1] = 3.0, 1.2                  # open ahead, a little more on the left
    steer(position, ranger(ranges), law, headings)
    dx = dy = 0.0
    for r, a in zip(ranges, headings, strict=True):   # added in order, as the C loop does
        dx += r * math.cos(a)                         # (Python 3.12's sum() compensates)
        dy += r * math.sin(a)
    assert commands[-1] == (0.3, 0.0, math.atan2(dy, dx))
    assert 0 < commands[-1][2] < 0.5                 # a small turn left
    ranges[1] = 0.3                                  # sensor 1 too close: turn only
    steer(position, ranger(ranges), law, headings)
    assert commands[-1][0] == 0.0


# ---- in a world ----------------------------------------------------------------------------
def test_wanderers_drive_in_stages_own_program_and_turn_before_the_wall(tmp_path):
    path = world_file(tmp_path, 'position( pose [ -3 0 0 0 ] size [ 0.4 0.4 0.3 ] laser( )'
                      ' ctrl "wander" )\n')
    w = load_world(path, stageros=False)
    r = w.robots[0]
    for _ in range(5):
        w.step()
    assert r.velocity[0] == wander.CRUISE_SPEED
    for _ in range(300):                               # 12 m at 0.4 m/s: the wall is 8 m away
        w.step()
        assert r.pose[0] < 4.7 and not r.stalled      # it turns away before the wall
    assert abs(r.pose[2]) > 0.5


def test_stages_program_moves_nothing_that_no_controller_subscribes(tmp_path):
    path = world_file(tmp_path, 'position( pose [ 0 0 0 0 ] )\n')
    still = load_world(path, stageros=False)
    moving = load_world(path)                         # stageros subscribes every robot
    for w in (still, moving):
        w.set_command(0, 0.2, 0.0, 0.0)
        for _ in range(10):
            w.step()
    assert still.robots[0].pose == (0.0, 0.0, 0.0)
    assert moving.robots[0].pose[0] == pytest.approx(0.2)


def test_the_same_world_runs_the_same_every_time_and_a_seed_changes_the_draws(tmp_path):
    path = world_file(tmp_path, ''.join(
        'position( pose [ %g %g 0 %d ] size [ 0.4 0.4 0.3 ] laser( ) ctrl "wander" )\n'
        % (x, y, a) for x, y, a in [(-3, -3, 10), (3, 3, 200), (-3, 3, 300), (2, -2, 45)]))

    def run(seed):
        w = load_world(path, seed=seed, stageros=False)
        for _ in range(300):
            w.step()
        return [r.pose for r in w.robots]
    assert run(None) == run(None)
    assert run(7) == run(7)
    assert run(7) != run(None)


def test_source_fills_up_to_its_capacity_and_sink_counts_deliveries(tmp_path):
    from stage_lite.controllers import sink
    path = world_file(tmp_path, 'model( pose [ 1 1 0 0 ] ctrl "source 3 ignored" )\n'
                      'model( pose [ -1 1 0 0 ] ctrl "sink" )\n')
    w = load_world(path, stageros=False)
    source, drop = (w.handle(m) for m in w.models[1:3])
    counts = []
    for _ in range(5):
        w.step()
        counts.append(source.get_flag_count())
    assert counts == [1, 2, 3, 3, 3]
    before = sink.delivered
    drop.push_flag(source.pop_flag())
    assert (sink.delivered - before, drop.get_flag_count(), source.get_flag_count()) == (1, 1, 2)


def test_lasernoise_scales_each_range_by_its_twelve_draws(tmp_path):
    body = 'position( pose [ 0 0 0 0 ] size [ 0.4 0.4 0.3 ] laser( %s ) )\n'
    clean = load_world(world_file(tmp_path, body % '', 'clean.world'))
    noisy = load_world(world_file(tmp_path, body % 'ctrl "lasernoise"'))
    clean.step()
    noisy.step()
    truth = clean.robots[0].rangers[0].sensor.ranges.copy()
    # the same stream by Stage's rules: the laser's queue drawn when it started, its scan's
    # own draws (every beam hits a wall), then the controller's twelve per beam
    stream = Random()
    stream.random()
    RangerNoise(stream).apply(truth, 8.0, (0.0, 0.0, 0.0))
    draws = stream.block(12 * len(truth)).reshape(len(truth), 12)
    factor = np.zeros(len(truth))
    for k in range(12):
        factor += draws[:, k] / 2.0 ** 31
    want = truth * (0.05 * (factor - 6.0) + 1.0)
    assert noisy.robots[0].rangers[0].sensor.ranges.tolist() == want.tolist()
    # and stageros publishes the scan as the controller left it
    assert noisy.robots[0].rangers[0].ranges.tolist() == want.astype(np.float32).tolist()


# ---- what can go wrong ---------------------------------------------------------------------
@pytest.mark.parametrize('ctrl, what', [
    ('"nosuch"', 'no controller "nosuch": not in STAGEPATH'),
    ('"source"', 'source needs its capacity'),
    ('"source many"', 'capacity must be a whole number, got "many"'),
    ('""', 'no controller named'),
])
def test_a_controller_stage_cannot_use_is_one_error_on_its_line(tmp_path, ctrl, what):
    path = world_file(tmp_path, 'model(\n  pose [ 0 0 0 0 ]\n  ctrl %s\n)\n' % ctrl)
    with pytest.raises(WorldError) as err:
        load_world(path, stageros=False)
    assert str(err.value).startswith('%s:%d:' % (path, ROOM.count('\n') + 3)), err.value
    assert what in str(err.value)


def test_wander_on_a_robot_without_a_laser_is_an_error_on_its_line(tmp_path):
    path = world_file(tmp_path, 'position( ctrl "wander" )\n')
    with pytest.raises(WorldError, match='has no ranger with more than 8 samples'):
        load_world(path, stageros=False)


MINE = '''
calls = []


def init(model, args):
    calls.append((model.token, args.worldfile, args.cmdline))
    model.subscribe()
    model.add_callback('update', tick, args.words()[1])


def tick(model, limit):
    model.set_speed(0.1, 0.0, 0.0)
    if model.world.update_count() >= int(limit):
        raise RuntimeError('enough')
'''


def test_my_own_python_controller_is_found_on_stagepath(tmp_path, monkeypatch):
    (tmp_path / 'mine.py').write_text(MINE)
    monkeypatch.setenv('STAGEPATH', '/nonexistent:%s' % tmp_path)
    path = world_file(tmp_path, 'position( name "r" ctrl "mine 3" )\n')
    logged = []
    w = load_world(path, stageros=False, ctrlargs='-v')
    w.log = logged.append
    for _ in range(10):
        w.step()
    # it drove until its callback raised, then the error was reported once, on its line
    assert len(logged) == 1 and logged[0].startswith('%s:%d: ctrl "mine 3" on r: '
                                                     'RuntimeError: enough' % (path, 5))
    # commanded from the first update on, moving from the second, and on after the error:
    # its last command stays, as in Stage
    assert w.robots[0].pose[0] == pytest.approx(9 * 0.01)
    assert w.robots[0].velocity[0] == 0.1


@pytest.mark.parametrize('source, what', [
    ('def init(:\n', 'the controller does not load: '),
    ('x = 1\n', 'has no init(model, args)'),
    ('def init(model, args):\n    raise KeyError("boom")\n', 'its init failed: KeyError'),
])
def test_a_broken_python_controller_is_one_error_naming_the_world_line(tmp_path, monkeypatch,
                                                                        source, what):
    (tmp_path / 'broken.py').write_text(source)
    monkeypatch.setenv('STAGEPATH', str(tmp_path))
    path = world_file(tmp_path, 'position( ctrl "broken" )\n')
    with pytest.raises(WorldError) as err:
        load_world(path, stageros=False)
    assert str(err.value).startswith('%s:%d: ctrl "broken"' % (path, 5)) and what in str(
        err.value), err.value


FLOCK = '''define sonars ranger( %s )
define finder fiducial( range_max 5 fov 360 )
define bot position( size [ 0.44 0.38 0.22 ] fiducial_return 1 sonars( ) finder( ) )
bot( name "a" pose [ -2 0.3 0 0 ] ctrl "pioneer_flocking" )
bot( name "b" pose [ 0 1.6 0 40 ] )
''' % ' '.join('sensor( pose [ 0 0 0 %d ] range [ 0 5 ] fov 15 samples 1 )' % a
               for a in (90, 50, 30, 10, -10, -30, -50, -90))


def test_pioneer_flocking_turns_toward_the_heading_of_the_robot_its_finder_sees(tmp_path):
    w = load_world(world_file(tmp_path, FLOCK), stageros=False)
    sonars, finder = (w.handle(m) for m in w.models[2:4])
    assert (sonars.type, finder.type) == ('ranger', 'fiducial')
    for _ in range(3):
        w.step()
    seen = finder.fiducials
    assert [(f.model.token, f.id) for f in seen] == [('b', 1)]
    (ax, ay, aa), (bx, by, ba) = (r.pose for r in w.robots)
    assert seen[0].range == pytest.approx(math.hypot(bx - ax, by - ay), abs=1e-9)
    heading_error = seen[0].geom[3]
    assert heading_error == pytest.approx(ba - aa, abs=1e-9)
    # the sonars' resultant, and the nearest robot's heading: both turn it (gain 0.3 each)
    first = [s.ranges[0] for s in sonars.sensors]
    headings = [s.pose.a for s in sonars.sensors]
    resultant = math.atan2(sum(r * math.sin(a) for r, a in zip(first, headings, strict=True)),
                           sum(r * math.cos(a) for r, a in zip(first, headings, strict=True)))
    goal = w.robots[0].goal
    assert goal[0] == 0.4
    assert goal[3] == pytest.approx(0.3 * resultant + 0.3 * heading_error, abs=0.01)
    assert abs(0.3 * heading_error) > 0.1


ORDER_CONTROLLER = '''
started = []


def init(model, args):
    started.append(model.token)
'''


def test_stages_model_order_sets_the_controllers_start_and_the_moves(tmp_path, monkeypatch):
    (tmp_path / 'note_start.py').write_text(ORDER_CONTROLLER)
    monkeypatch.setenv('STAGEPATH', str(tmp_path))
    # two robots driving head on into the same gap: the one Stage moves first takes it
    path = world_file(tmp_path, 'position( name "p" pose [ -0.24 0 0 0 ] size [ 0.2 0.2 0.3 ]'
                      ' ctrl "note_start" )\n'
                      'position( name "q" pose [ 0.24 0 0 180 ] size [ 0.2 0.2 0.3 ]'
                      ' ctrl "note_start" )\n')

    def run(order):
        w = load_world(path, model_order=order)
        noted = sys.modules['stage_ctrl_note_start'].started   # one module, as Stage's .so
        started = noted[-2:]
        for i in range(2):
            w.set_command(i, 0.5, 0.0, 0.0)
        stalls = [False, False]
        while not any(stalls):             # the first step one of them hits the other
            w.step()
            stalls = [r.stalled for r in w.robots]
        return started, stalls
    assert run(None) == (['p', 'q'], [False, True])         # file order
    assert run(['q', 'p']) == (['q', 'p'], [True, False])     # Stage's, as given


def test_rasterize_prints_each_bodys_outline_as_the_real_stage_does(capsys):
    """Three bodies (an octagon scaled to its size, the default box turned 30 degrees, a
    triangle and a sliver in one body): the real Stage's output, line for line, with its
    quirks (the raster's far edges fall outside it; an edge that starts outside stays on
    its row)."""
    here = os.path.dirname(os.path.abspath(__file__))
    load_world(os.path.join(here, '..', 'worlds', 'rasterize.world'), stageros=False)
    with open(os.path.join(here, '..', 'golden', 'data', 'rasterize.txt')) as f:
        real = f.read().splitlines()
    ours = [line for line in capsys.readouterr().out.splitlines() if line]
    assert ours == real
    assert len(real) == 3 * 22


def test_a_raster_skips_what_falls_outside_it():

    square = Block([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)], 0.0, 1.0)
    data = rasterize([square], (2.0, 2.0, 1.0), 4, 4, 0.5, 0.5)
    rows = [''.join('O' if v else '.' for v in data[y * 4:(y + 1) * 4]) for y in range(4)]
    # the right and top edges lie on x = 4 and y = 4 cells: outside a 4 x 4 raster
    assert rows == ['OOOO', 'O...', 'O...', 'O...']
