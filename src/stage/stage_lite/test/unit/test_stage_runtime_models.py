"""Models made at run time (World::CreateModel, SetPose, SetGeom, SetColor), Stage's two
controllers that need them or ranger:1, `dynamic` and `wander_accel`, and acceleration
control, held to the real Stage 4.3.0 on the repository's worlds (golden/data/dynamic.txt,
wander_accel.npz, accel.npz: how they were made is in golden/README.md)."""
import os

import numpy as np
import pytest
from stage_lite.model.stage_api import Pose
from stage_lite.model.world import WorldError, load_world

HERE = os.path.dirname(os.path.abspath(__file__))
WORLDS = os.path.join(HERE, '..', 'worlds')
DATA = os.path.join(HERE, '..', 'golden', 'data')
ROOM = '''resolution 0.02
interval_sim 100
define laser ranger ( sensor( range [ 0 5 ] fov 180 samples 61 ) )
'''


def golden_dynamic(name='dynamic.txt'):
    """The real Stage's printout: {token: MODEL words}, {token: ERROR words}, POSE words per
    step, {step time: [the scans the runs gave]}."""
    models, errors, poses, scans = {}, {}, [], {}
    with open(os.path.join(DATA, name)) as f:
        for line in f:
            w = line.split()
            if w[0] == 'MODEL':
                models[w[1]] = w
            elif w[0] == 'ERROR':
                errors[w[1]] = [float(v) for v in w[2:]]
            elif w[0] == 'POSE':
                poses.append(w)
            elif w[0] == 'SCAN':
                scans.setdefault(int(w[1]), []).append([float(v) for v in w[3:]])
    return models, errors, poses, scans


def numbers(words, name, count):
    at = words.index(name) + 1
    return [float(v) for v in words[at:at + count]]


def depth_first(world):
    """The models as World::ForEachDescendant walks them: each top-level model, then its
    children, depth first."""
    out = []
    stack = [m for m in world.models if m.parent is None][::-1]
    while stack:
        m = stack.pop()
        out.append(m)
        stack.extend(m.children[::-1])
    return out


def model_named(world, token):
    return next(m for m in world.models if m.token == token)


def test_dynamic_makes_the_real_stages_100_boxes_to_the_last_bit(capsys):
    """Tokens, parents, poses (Pose::Random's drand48 draws after the robot's constructor's
    four), geometry and colours: every model the real Stage listed, equal, in its order."""
    world = load_world(os.path.join(WORLDS, 'dynamic.world'), stageros=False)
    assert capsys.readouterr().out == 'Creating 100 models'     # no newline, as Stage's
    models, errors, _, _ = golden_dynamic()
    del models['_ground_model']                  # Stage's own, not a world's model
    assert [m.token for m in depth_first(world)] == list(models)    # Stage's tree walk
    for m in world.models:
        real = models[m.token]
        assert (m.parent.token if m.parent else '-') == real[4]
        assert list(m.pose) == numbers(real, 'local', 4), m.token
        assert list(m.global_pose()) == numbers(real, 'global', 4), m.token
        assert list(m.geom_pose) + list(m.geom_size) == (numbers(real, 'geom', 4)
                                                         + numbers(real, 'size', 3)), m.token
        assert list(m.color) == numbers(real, 'color', 4), m.token
    assert list(model_named(world, 'bot').integration_error) == errors['bot']
    boxes = [m for m in world.models if m.parent is not None and m.parent.token == 'pad']
    assert len(boxes) == 100 and len({m.pose for m in boxes}) == 100


def drive_into_the_boxes(path):
    world = load_world(path, stageros=False)
    bot = world.handle(model_named(world, 'bot'))
    bot.subscribe()
    bot.get_child('ranger:0').subscribe()
    bot.set_speed(0.3, 0.0, 0.0)
    return world


def test_a_robot_sees_the_boxes_and_stalls_on_them_as_in_the_real_stage(capsys):
    """Every pose and stall equal to the real Stage's, and every scan one a real run gave
    (its rangers race the moves in a worker thread); the robot stalls on a box at step 28."""
    world = drive_into_the_boxes(os.path.join(WORLDS, 'dynamic.world'))
    _, _, poses, scans = golden_dynamic()
    robot = world.robots[0]
    for k in range(1, len(poses)):
        world.step()
        real = poses[k]
        x, y, _, a = robot.model.pose
        assert [x, y, a, int(robot.stalled)] == [float(v) for v in real[3:6]] + [int(real[6])]
        scan = robot.rangers[0].model.sensors[0].ranges.tolist()
        assert scan in scans[int(real[1])], k
    stall_steps = [int(p[1]) for p in poses if p[6] == '1']
    assert stall_steps[0] == 2800000 and len(poses) > 29


def test_dynamic_on_a_robot_carries_its_boxes_as_the_real_stage(capsys):
    """The boxes ride on a position model driven backwards and turning: every model at load
    and every pose and stall to the last bit (it stalls when a box touches the other robot,
    step 29), and every scan of the other robot the one its laser casts before the step's
    moves, as the real Stage's ranger thread did in all six runs (it reads the same layer
    either way, but the moving boxes' regions, walked or jumped, are those it then finds;
    cast after the moves, as stage_lite casts, two of the 40 scans differ)."""
    world = load_world(os.path.join(WORLDS, 'dynamic_carried.world'), stageros=False)
    models, errors, poses, scans = golden_dynamic('dynamic_carried.txt')
    del models['_ground_model']
    assert [m.token for m in depth_first(world)] == list(models)
    for m in world.models:
        real = models[m.token]
        assert list(m.global_pose()) + list(m.geom_size) + list(m.color) == (
            numbers(real, 'global', 4) + numbers(real, 'size', 3) + numbers(real, 'color', 4))
    for token, speed in (('carrier', (-0.3, 0.0, 0.1)), ('bot', (0.0, 0.0, 0.0))):
        robot = world.handle(model_named(world, token))
        robot.subscribe()
        for child in robot.children:
            child.subscribe()
        robot.set_speed(*speed)
    real_pose = {(int(p[1]), p[2]): [float(v) for v in p[3:6]] + [int(p[6])] for p in poses}
    laser = world.robots[1].rangers[0].model
    slot = world._ranger_slot[laser.index]
    sensors = np.arange(world._ranger_sensor_off[slot], world._ranger_sensor_off[slot + 1])
    after_the_moves = 0

    def poses_equal(k):
        for r in world.robots:
            x, y, _, a = r.model.pose
            assert [x, y, a, int(r.stalled)] == real_pose[(k * 100000, r.model.token)], k

    world.step()                  # the first (the grid is made again with the boxes)
    poses_equal(1)
    for k in range(2, len(poses) // 2):
        stream = world.random.state()             # a cast draws each beam's noise
        world.cast_rays(sensors, (world.updates + 1) % 2)
        before_the_moves = laser.sensors[0].ranges.tolist()
        world.random.table[:], world.random.pointers[:] = stream
        world.step()
        poses_equal(k)
        assert before_the_moves in scans[k * 100000], k
        after_the_moves += laser.sensors[0].ranges.tolist() in scans[k * 100000]
    assert world.robots[0].stalled and after_the_moves == 37     # all but steps 9, 14


def test_without_the_boxes_the_same_robot_sees_nothing_and_drives_on(tmp_path, capsys):
    """What the robot saw and hit above is the boxes: without `dynamic` only the pad is
    there, below its laser's beams and its body's reach."""
    with open(os.path.join(WORLDS, 'dynamic.world')) as f:
        text = f.read().replace(' ctrl "dynamic"', '')
    path = tmp_path / 'no_boxes.world'
    path.write_text(text)
    world = drive_into_the_boxes(str(path))
    for _ in range(32):
        world.step()
        assert (world.robots[0].rangers[0].model.sensors[0].ranges == 5.0).all()
    assert not world.robots[0].stalled


def test_a_model_made_at_run_time_has_stages_defaults_and_is_drawn_once_posed(tmp_path):
    path = tmp_path / 'w.world'
    path.write_text(ROOM + 'model( name "m" pose [ 5 5 0 0 ] )\n'
                    'position( name "r" size [ 0.2 0.2 0.05 ] laser( ) )\n')
    world = load_world(str(path), stageros=False)
    api = world.handle(model_named(world, 'r')).world
    top = api.create_model(None, 'model')
    child = api.create_model(top, 'model')
    other = api.create_model(api.get_model('m'), 'model')
    # tokens as Stage makes them: the world's ground model is model:0, "m" model:1
    assert [top.token, child.token, other.token] == ['model:2', 'model:2.model:0',
                                                     'm.model:0']
    assert api.get_model('model:2.model:0') is child and child.parent is top
    assert top.get_geom() == (Pose(), (0.4, 0.4, 1.0)) and top.color == (1, 0, 0, 1)
    assert model_named(world, 'model:2').blocks[0].pts.tolist() == [
        [-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]   # not scaled to its size
    robot = world.handle(model_named(world, 'r'))
    robot.subscribe()
    robot.get_child('ranger:0').subscribe()
    beams = robot.get_child('ranger:0').sensors[0].ranges

    top.set_color((0, 1, 0, 1))              # not drawn yet: the laser sees nothing
    world.step()
    assert (beams == 5.0).all()
    top.set_pose((1.0, 0.0, 0.0, 0.0))       # a 1 m cube whose near face is 0.5 m ahead
    world.step()
    world.step()
    assert beams[30] == pytest.approx(0.5, abs=0.03)
    top.set_geom(Pose(), (0.2, 0.2, 0.2))    # now its near face is 0.9 m ahead
    world.step()
    world.step()
    assert beams[30] == pytest.approx(0.9, abs=0.03)
    robot.set_speed(1.0, 0.0, 0.0)           # and the robot stalls on it
    for _ in range(12):
        world.step()
    assert robot.stalled() and robot.get_pose().x == pytest.approx(0.8, abs=0.06)


def test_cameras_and_the_map_see_a_model_made_at_run_time(tmp_path):
    path = tmp_path / 'cam.world'
    path.write_text('resolution 0.02\nmodel( pose [ 3.1 0 0 0 ] size [ 0.2 6 1 ] )\n'
                    'position( size [ 0.3 0.3 0.2 ] camera( resolution [ 32 24 ] ) )\n')
    world = load_world(str(path))
    view = world.cameras.views[0]
    world.step()
    assert view.depth[12, 16] == pytest.approx(3.0, rel=1e-6)     # the wall's near face
    floor = world.occupancy()[0].sum()
    box = world.handle(world.models[0]).world.create_model(None, 'model')
    box.set_pose((1.6, 0.0, 0.0, 0.0))
    box.set_geom(Pose(), (0.2, 0.2, 1.0))
    world.step()
    assert view.depth[12, 16] == pytest.approx(1.5, rel=1e-6)     # the box's near face
    assert world.occupancy()[0].sum() > floor


def test_a_blobfinder_sees_a_model_made_at_run_time(tmp_path):
    path = tmp_path / 'blob.world'
    path.write_text('resolution 0.02\nposition( name "me" size [ 0.4 0.4 0.25 ]'
                    ' blobfinder( colors_count 1 colors [ "blue" ] ) )\n')
    world = load_world(str(path), stageros=False)
    finder = world.handle(model_named(world, 'me.blobfinder:0'))
    finder.subscribe()
    world.step()
    assert finder.blobs == []
    box = finder.world.create_model(None, 'model')
    box.set_pose((2.0, 0.0, 0.0, 0.0))
    box.set_geom(Pose(), (0.5, 0.5, 0.5))
    box.set_color((0.0, 0.0, 1.0, 1.0))
    world.step()
    world.step()
    assert len(finder.blobs) == 1
    assert finder.blobs[0].range == pytest.approx(1.75, abs=0.03)    # its near face


@pytest.mark.parametrize('parent, kind, what', [
    (None, 'nosuch', 'Model type nosuch not found in model typetable'),
    (None, 'position', 'a position made at run time is not simulated here'),
    ('r', 'model', 'models are made on a moving model before the first step only'),
])
def test_what_cannot_be_made_at_run_time_is_one_clear_error(tmp_path, parent, kind, what):
    path = tmp_path / 'w.world'
    path.write_text(ROOM + 'position( name "r" )\n')
    world = load_world(str(path), stageros=False)
    api = world.handle(world.models[0]).world
    carried = api.create_model(api.get_model('r'), 'model')    # before the first step: yes
    world.step()
    with pytest.raises(ValueError, match=what):
        api.create_model(api.get_model(parent) if parent else None, kind)
    for model in (world.handle(world.models[0]), carried):
        with pytest.raises(ValueError, match='a carried model is moved only if made at run'
                                             ' time, before the first step'):
            model.set_pose((1, 0, 0, 0))
    box = api.create_model(None, 'model')
    with pytest.raises(ValueError, match='model:1: pose must be finite'):
        box.set_pose((float('nan'), 0, 0, 0))


@pytest.mark.parametrize('body, what', [
    ('model( ctrl "dynamic 50" )', 'dynamic takes no arguments'),
    ('model( ctrl "wander_accel" )', 'wander_accel drives a position model, not a model'),
    ('position( ctrl "wander_accel" laser( ) )', 'has no position:0.ranger:1 with a sensor'),
    ('position( ctrl "wander_accel fast" )', 'wander_accel takes no arguments'),
])
def test_dynamic_and_wander_accel_refuse_what_they_cannot_run_on_its_line(tmp_path, body,
                                                                           what, capsys):
    path = tmp_path / 'w.world'
    path.write_text(ROOM + '\n' + body + '\n')
    with pytest.raises(WorldError) as err:
        load_world(str(path), stageros=False)
    assert str(err.value).startswith('%s:%d: ctrl "' % (path, ROOM.count('\n') + 2))
    assert what in str(err.value), err.value


def test_wander_accel_drives_as_the_real_stage_pose_for_pose():
    """Two robots wandering for 60 s: every pose and stall of a real run, to the last bit
    (golden/README.md: the real runs part from each other when a ranger races a move)."""
    real = np.load(os.path.join(DATA, 'wander_accel.npz'))
    world = load_world(os.path.join(WORLDS, 'wander_accel.world'), stageros=False)
    assert [r.model.token for r in world.robots] == real['robots'].tolist()
    pose, stall = real['pose'][0], real['stall'][0]
    turned = 0
    for k in range(len(real['t_us'])):
        if k:
            world.step()
        ours = np.array([[r.model.pose[i] for i in (0, 1, 3)] for r in world.robots])
        assert np.array_equal(ours, pose[k]), k
        assert [int(r.stalled) for r in world.robots] == stall[k].tolist(), k
        turned += any(r.velocity[3] != 0.0 for r in world.robots)
    assert turned > 50          # they avoided walls and each other, not only cruised


def test_wander_accel_takes_ranger_1_whatever_its_samples(tmp_path):
    path = tmp_path / 'w.world'
    path.write_text(ROOM + 'define few ranger ( sensor( range [ 0 5 ] samples 3 ) )\n'
                    'position( name "r" laser( ) few( ) ctrl "wander_accel" )\n')
    world = load_world(str(path), stageros=False)
    world.step()
    world.step()
    assert world.robots[0].velocity[0] == 0.4        # cruising on ranger:1's 3 beams
    assert world.scheduler.subscribed(model_named(world, 'r.ranger:1'))
    assert not world.scheduler.subscribed(model_named(world, 'r.ranger:0'))


def test_acceleration_control_moves_robots_as_the_real_stage():
    """SetAcceleration, held to the real Stage to the last bit for 10 s: a diff robot
    speeding up to its velocity bound and stalling on a wall, an omni robot under tighter
    acceleration and velocity bounds, a car that Stage does not accelerate (it stands)."""
    real = np.load(os.path.join(DATA, 'accel.npz'))
    world = load_world(os.path.join(WORLDS, 'accel.world'), stageros=False)
    commands = {'diff': (0.4, 0.0, 0.0), 'omni': (0.3, 0.5, 0.1), 'car': (0.3, 0.0, 0.1)}
    for r in world.robots:
        robot = world.handle(r.model)
        robot.subscribe()
        robot.set_acceleration(*commands[r.model.token])
    assert [r.model.token for r in world.robots] == real['robots'].tolist()
    for k in range(len(real['t_us'])):
        if k:
            world.step()
        ours = np.array([[r.model.pose[i] for i in (0, 1, 3)] for r in world.robots])
        assert np.array_equal(ours, real['pose'][0, k]), k
        assert [int(r.stalled) for r in world.robots] == real['stall'][0, k].tolist(), k
    assert real['stall'][0, -1].tolist() == [1, 0, 0]
    assert world.robots[0].velocity[0] == 1.0 and world.robots[1].velocity[:2] == (0.5, 0.5)


def test_a_fiducial_finder_sees_a_static_model_where_it_was_moved(tmp_path):
    # the finders' sets and readings take a static model's pose from a cache that a move
    # must clear (World.global_poses); a robot beside it keeps the sets mixed
    path = tmp_path / 'beacon.world'
    path.write_text('resolution 0.02\n'
                    'position( name "me" size [ 0.4 0.4 0.25 ] fiducial( range_max 8 ) )\n'
                    'position( name "mate" pose [ 0 -2 0 0 ] size [ 0.4 0.4 0.25 ]'
                    ' fiducial_return 2 )\n'
                    'model( name "beacon" pose [ 2 0 0 0 ] size [ 0.2 0.2 0.5 ]'
                    ' fiducial_return 1 )\n')
    world = load_world(str(path), stageros=False)
    finder = world.handle(model_named(world, 'me.fiducial:0'))
    finder.subscribe()

    def ranges():
        world.step()
        return {seen.id: seen.range for seen in finder.fiducials}
    before = ranges()
    assert before[1] == pytest.approx(2.0, abs=1e-9)
    assert before[2] == pytest.approx(2.0, abs=1e-9)
    world.handle(model_named(world, 'beacon')).set_pose((2.4, 1.8, 0.0, 0.0))
    after = ranges()
    assert after[1] == pytest.approx(3.0, abs=1e-9)
    assert after[2] == pytest.approx(2.0, abs=1e-9)
