"""Stage's fiducial finder (stage_lite.model.fiducial, its rays through sight.py): what a finder
sees, what hides a model from it, its readings' fields and their order; with the blobfinder,
every digit of real Stage's first readings on two worlds."""
import math
import os

import numpy as np
import pytest
from stage_lite.model import raytrace
from stage_lite.model.fiducial import Fiducial, FiducialIndex
from stage_lite.model.ranger import Ranger
from stage_lite.model.sight import Sight
from stage_lite.model.world import load_world

ROBOT = 'size [ 0.4 0.4 0.25 ]'      # the finder on it looks from z = 0.25
WORLDS = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'worlds')

#: Real Stage 4.3.0's first readings (stage -g, a controller subscribing the finders and
#: printing every digit): per robot, its blobfinder's blobs (colour r g b, left top right
#: bottom, range), then its fiducial finder's readings (model, range, bearing, geom, id).
REAL_STAGE = {
    'finders_a.world': {
        'me': ([
            '0 0 1 55 26 60 34 2.0133932265918939',
            '0 0 1 39 28 41 32 4.2664040585784422',
            '0 1 0 12 25 20 35 1.6972934431514155',
        ], [
            'you 1.9374725804511403 0.6108652381980153 0.5 0.29999999999999999 0.5'
            ' 0.4014257279586958 5',
            'seen 2.1637467504308359 -0.46997376234315291 0.29999999999999999'
            ' 0.29999999999999999 0.5 -0.52359877559829882 7',
            'far 4.4210632205386977 -0.022399503895111861 0.29999999999999999'
            ' 0.29999999999999999 0.5 -0.17453292519943295 0',
            'behind 3.3301351323932789 1.5865919412873708 0.29999999999999999'
            ' 0.29999999999999999 0.5 -0.17453292519943295 0',
        ]),
    },
    'finders_b.world': {
        'me': ([
            '0.30196078431372547 0.30196078431372547 0.30196078431372547 68 15 100 15'
            ' 3.7008340932919097',
            '0 0 1 58 14 66 16 2.1089028093200941',
            '1 0 0 51 14 56 16 1.923577792511866',
            '0.30196078431372547 0.30196078431372547 0.30196078431372547 21 15 49 15'
            ' 4.2524680432255604',
            '0 1 0 13 14 19 16 1.7336639488050081',
            '0.30196078431372547 0.30196078431372547 0.30196078431372547 0 15 11 15'
            ' 4.8180635610068361',
        ], [
            'you 2.0064396327824068 1.1461657545353301 0.5 0.29999999999999999 0.5'
            ' 1.0995574287564276 5',
            'r1 2.0634437234875098 0.16199203805913315 0.29999999999999999'
            ' 0.29999999999999999 0.5 0.69813170079773179 3',
            'b2 2.3438856627403992 -0.079787229729863962 0.29999999999999999'
            ' 0.29999999999999999 0.050000000000000003 0.69813170079773179 4',
            'o1 2.1292721761202817 -1.7461450629066722 0.59999999999999998'
            ' 0.20000000000000001 1.5 1.7453292519943293 6',
        ]),
        'you': ([], None),
    },
}


def world(tmp_path, body):
    p = tmp_path / 'w.world'
    p.write_text('resolution 0.02\n' + body + '\n')
    return load_world(str(p))


class Scene:
    """A loaded world with its fiducial index and rays, stepped by hand as a World would."""

    def __init__(self, tmp_path, body):
        self.world = world(tmp_path, body)
        self.index = FiducialIndex(self.world.models)
        self.sight = Sight(self.world.models, self.world.robots, self.world.space)

    def model(self, name):
        return next(m for m in self.world.models if m.name == name)

    def finder(self, k=0):
        return [m for m in self.world.models if isinstance(m, Fiducial)][k]

    def readings(self, k=0):
        self.index.begin_step()
        return self.finder(k).update(self.index, self.sight, (self.world.updates + 1) % 2)

    def seen(self, k=0):
        return [(r.model.name, r.id) for r in self.readings(k)]


def one_target(tmp_path, target, finder='', robot='pose [ 0 0 0 0 ]'):
    return Scene(tmp_path, 'position( name "me" %s %s fiducial( %s ) )\n%s'
                 % (ROBOT, robot, finder, target))


def test_defaults_are_stages():
    f = Fiducial('', None, 'fiducial', 0, 0, {})
    assert (f.range_min, f.range_max, f.range_max_id, f.fov, f.ignore_zloc) == (
        0.0, 8.0, 5.0, math.pi, False)
    assert f.blocks == [] and f.geom_size == (0.0, 0.0, 0.0)
    assert (f.fiducial_return, f.fiducial_key) == (0, 0)


def test_properties_are_read_in_stages_units(tmp_path):
    s = one_target(tmp_path, '', 'range_min 0.5 range_max 4 range_max_id 2 fov 90 ignore_zloc 1'
                   ' fiducial_key 3')
    f = s.finder()
    assert (f.range_min, f.range_max, f.range_max_id, f.ignore_zloc, f.fiducial_key) == (
        0.5, 4.0, 2.0, True, 3)
    assert f.fov == pytest.approx(math.pi / 2, abs=1e-15)
    assert not [w for w in s.world.warnings if 'not used' in w]


def test_a_model_in_view_is_read_at_its_range_and_bearing(tmp_path):
    # the finder at (0, 0) facing +y; the box at (1, 2) turned 30 degrees
    s = one_target(tmp_path, 'model( name "box" pose [ 1 2 0 30 ] size [ 0.3 0.4 0.5 ]'
                   ' fiducial_return 7 )', robot='pose [ 0 0 0 90 ]')
    [r] = s.readings()
    assert r.model is s.model('box')
    assert r.range == pytest.approx(math.sqrt(5.0), abs=1e-15)
    assert r.bearing == pytest.approx(math.atan2(2.0, 1.0) - math.pi / 2, abs=1e-15)
    assert r.geom == pytest.approx((0.3, 0.4, 0.5, math.radians(30 - 90)), abs=1e-15)
    assert r.pose == pytest.approx((1.0, 2.0, 0.0, math.radians(30)), abs=1e-15)
    assert r.id == 7


@pytest.mark.parametrize('wall', [
    '',                                      # a plain wall
    'ranger_return -1 obstacle_return 0',    # invisible to rangers, no obstacle: still a wall
])
def test_a_wall_in_between_hides_it(tmp_path, wall):
    target = 'model( name "box" pose [ 3 0 0 0 ] size [ 0.3 0.3 0.5 ] fiducial_return 7 )\n'
    assert one_target(tmp_path, target).seen() == [('box', 7)]
    hidden = one_target(tmp_path, target + 'model( pose [ 1.5 0 0 0 ] size [ 0.1 1 0.5 ] %s )'
                        % wall)
    assert hidden.seen() == []


def test_a_wall_beside_the_line_of_sight_hides_nothing(tmp_path):
    s = one_target(tmp_path, 'model( name "box" pose [ 3 0 0 0 ] size [ 0.3 0.3 0.5 ]'
                   ' fiducial_return 7 )\nmodel( pose [ 1.5 0.5 0 0 ] size [ 0.1 0.5 0.5 ] )')
    assert s.seen() == [('box', 7)]


@pytest.mark.parametrize('where, seen', [
    ('pose [ 2 1.9 0 0 ]', True),     # bearing 43.5 degrees: inside +-45
    ('pose [ 2 2.1 0 0 ]', False),    # 46.4 degrees: outside
    ('pose [ -2 0 0 0 ]', False),     # behind
    ('pose [ 2.99 0 0 0 ]', True),    # inside range_max 3
    ('pose [ 3 0 0 0 ]', False),      # at range_max: not seen (range >= range_max)
])
def test_fov_and_range_max(tmp_path, where, seen):
    s = one_target(tmp_path, 'model( name "box" %s size [ 0.3 0.3 0.5 ] fiducial_return 7 )'
                   % where, 'range_max 3 fov 90')
    assert s.seen() == ([('box', 7)] if seen else [])


@pytest.mark.parametrize('x, expected_id', [(1.99, 7), (2.0, 0), (2.5, 0)])
def test_beyond_range_max_id_the_id_is_0(tmp_path, x, expected_id):
    s = one_target(tmp_path, 'model( name "box" pose [ %s 0 0 0 ] size [ 0.3 0.3 0.5 ]'
                   ' fiducial_return 7 )' % x, 'range_max 3 range_max_id 2')
    [r] = s.readings()
    assert r.id == expected_id and r.range == pytest.approx(x, abs=1e-15)


def test_its_own_robot_is_never_seen_but_the_others_finder_sees_it(tmp_path):
    s = Scene(tmp_path, 'position( name "a" pose [ 0 0 0 0 ] %s fiducial_return 1 fiducial( ) )\n'
              'position( name "b" pose [ 2 0 0 180 ] %s fiducial_return 2 fiducial( ) )'
              % (ROBOT, ROBOT))
    assert s.seen(0) == [('b', 2)]
    assert s.seen(1) == [('a', 1)]


def test_a_model_on_the_finders_robot_is_related_and_not_seen(tmp_path):
    s = Scene(tmp_path, 'position( name "a" pose [ 0 0 0 0 ] %s fiducial( )'
              ' model( name "mast" pose [ 1 0 0 0 ] size [ 0.1 0.1 0.1 ] fiducial_return 5 ) )'
              % ROBOT)
    assert s.seen() == []


def test_keys_must_match(tmp_path):
    box = 'model( name "box" pose [ 2 0 0 0 ] size [ 0.3 0.3 0.5 ] fiducial_return 7 %s )'
    assert one_target(tmp_path, box % 'fiducial_key 1').seen() == []
    assert one_target(tmp_path, box % 'fiducial_key 1', 'fiducial_key 1').seen() == [('box', 7)]
    assert one_target(tmp_path, box % '', 'fiducial_key 1').seen() == []


def test_negative_returns_are_seen(tmp_path):
    assert one_target(tmp_path, 'model( name "box" pose [ 2 0 0 0 ] size [ 0.3 0.3 0.5 ]'
                      ' fiducial_return -3 )').seen() == [('box', -3)]


def test_a_box_below_the_finders_height_is_seen_only_with_ignore_zloc(tmp_path):
    # the finder on a 1 m tall robot looks at z = 1.0, over a 0.5 m box
    tall = 'size [ 0.4 0.4 1.0 ]'
    box = 'model( name "box" pose [ 2 0 0 0 ] size [ 0.3 0.3 0.5 ] fiducial_return 7 )\n'
    scene = 'position( name "me" pose [ 0 0 0 0 ] %s fiducial( %s ) )\n%s%s'
    assert Scene(tmp_path, scene % (tall, '', box, '')).seen() == []
    assert Scene(tmp_path, scene % (tall, 'ignore_zloc 1', box, '')).seen() == [('box', 7)]
    # the ray passes over the box and meets a tall wall: with ignore_zloc too, not seen
    wall = 'model( pose [ 3 0 0 0 ] size [ 0.1 1 2 ] )'
    assert Scene(tmp_path, scene % (tall, 'ignore_zloc 1', box, wall)).seen() == []
    # a box whose top is exactly the finder's height is seen (ends included)
    flush = box.replace('0.5 ]', '1.0 ]')
    assert Scene(tmp_path, scene % (tall, '', flush, '')).seen() == [('box', 7)]


def test_a_model_without_a_body_is_seen_only_with_ignore_zloc(tmp_path):
    ghost = 'model( name "ghost" pose [ 2 0 0 0 ] noblocks 1 fiducial_return 4 )'
    assert one_target(tmp_path, ghost).seen() == []
    assert one_target(tmp_path, ghost, 'ignore_zloc 1').seen() == [('ghost', 4)]


def test_readings_come_in_the_models_load_order_not_by_distance(tmp_path):
    # Stage's candidates are a std::set of model pointers: the order models were allocated
    s = one_target(tmp_path, '\n'.join(
        'model( name "%s" pose [ %s ] size [ 0.2 0.2 0.5 ] fiducial_return %d )' % (n, p, k)
        for k, (n, p) in enumerate([('far', '4 0.5 0 0'), ('near', '1 -0.5 0 0'),
                                    ('mid', '2.5 1.5 0 0'), ('left', '0.5 2 0 0')], 1)))
    assert s.seen() == [('far', 1), ('near', 2), ('mid', 3), ('left', 4)]


def test_the_order_can_be_real_stages_address_order(tmp_path):
    # fasr.world's charge stations, file order 1..7, come 1 3 2 6 4 5 7 out of real Stage
    s = one_target(tmp_path, '\n'.join(
        'model( name "c%d" pose [ %r %r 0 0 ] size [ 0.2 0.2 0.5 ] fiducial_return 2 )'
        % (k, 2 * math.cos(math.radians(20 * (k - 4))), 2 * math.sin(math.radians(20 * (k - 4))))
        for k in range(1, 8)))
    order = {'c%d' % k: i for i, k in enumerate([1, 3, 2, 6, 4, 5, 7])}
    s.index = FiducialIndex(s.world.models, rank=lambda m: order[m.name])
    assert [name for name, _ in s.seen()] == ['c1', 'c3', 'c2', 'c6', 'c4', 'c5', 'c7']


def test_set_return_at_run_time_is_honoured_from_the_next_step(tmp_path):
    s = one_target(tmp_path, 'model( name "box" pose [ 2 0 0 0 ] size [ 0.3 0.3 0.5 ] )')
    box = s.model('box')
    assert s.index.models == []
    assert s.seen() == []
    s.index.set_return(box, 9)
    assert s.index.models[-1] is box
    # within the step the candidates are the sets made at its start: not yet
    layer = (s.world.updates + 1) % 2
    assert s.finder().update(s.index, s.sight, layer) == []
    assert s.seen() == [('box', 9)]           # the next step rebuilds them
    s.index.set_return(box, 0)
    assert box not in s.index.models
    # still a candidate until the sets are rebuilt: seen, with its return now 0
    assert [(r.model.name, r.id) for r in s.finder().update(s.index, s.sight, layer)] == [
        ('box', 0)]
    assert s.seen() == []


def test_set_return_moves_the_model_to_the_end_of_the_list(tmp_path):
    s = one_target(tmp_path, 'model( name "a" fiducial_return 1 )\n'
                   'model( name "b" fiducial_return 2 )')
    a, b = s.model('a'), s.model('b')
    assert s.index.models == [a, b]
    s.index.set_return(a, 3)
    assert s.index.models == [b, a] and a.fiducial_return == 3
    s.index.set_key(a, 4)
    assert a.fiducial_key == 4


def test_a_moving_robot_is_followed(tmp_path):
    s = Scene(tmp_path, 'position( name "me" pose [ 0 0 0 0 ] %s fiducial( ) )\n'
              'position( name "other" pose [ 2 0 0 90 ] %s fiducial_return 5 )' % (ROBOT, ROBOT))
    s.world.set_command(1, 1.0, 0.0, 0.0)
    for _ in range(10):
        s.world.step()
    [r] = s.readings()
    x, y, _, a = s.model('other').global_pose()
    assert (x, y) == pytest.approx((2.0, 1.0), abs=1e-9)
    assert r.range == pytest.approx(math.hypot(x, y), abs=1e-15)
    assert r.bearing == pytest.approx(math.atan2(y, x), abs=1e-15)
    assert r.geom[3] == pytest.approx(math.pi / 2, abs=1e-15)


@pytest.mark.parametrize('coord, inside', [
    (-3.0, False),                  # at x - range: the low bound excludes ties
    (-2.999, True),
    (3.0, True),                    # at x + range: the high bound includes ties
    (3.001, False)])
def test_the_candidate_box_bounds(tmp_path, coord, inside):
    s = one_target(tmp_path, 'model( name "t" pose [ %s 0 0 0 ] fiducial_return 1 )\n'
                   'model( name "u" pose [ 0 %s 0 0 ] fiducial_return 2 )' % (coord, coord),
                   'range_max 3')
    s.index.begin_step()
    names = [m.name for m in s.index.nearby(0.0, 0.0, 3.0)]
    assert names == (['t', 'u'] if inside else [])


def test_a_finder_on_a_static_model_sees_past_its_own_body(tmp_path):
    s = Scene(tmp_path, 'model( name "post" pose [ 0 0 0 0 ] size [ 0.4 0.4 0.5 ]'
              ' fiducial( pose [ 0 0 -0.25 0 ] ) )\n'
              'model( name "box" pose [ 2 0 0 0 ] size [ 0.3 0.3 0.5 ] fiducial_return 7 )')
    assert s.seen() == [('box', 7)]



def test_the_kernel_is_the_rule_as_written_in_crowds_and_at_the_edges(tmp_path):
    # update() (finders.py's kernel: marks, ranks, its cheap tests first) against
    # update_one_by_one() (the rule in Python, candidate by candidate): many targets in a
    # shuffled rank, a few or most of them in a finder's box (the kernel ranks a few by
    # sorting, many by a pass over all), some exactly on the field of view's and the
    # range's edges, with fovs of 0, 90, 180, 300 and 360 degrees
    rng = np.random.default_rng(7)
    # tolist(): Python floats, whose %r is the number (numpy 2's is np.float64(...))
    targets = ['model( name "t%d" pose [ %r %r 0 %r ] size [ 0.2 0.2 0.5 ]'
               ' fiducial_return %d )' % (k, x, y, a, k + 1)
               for k, (x, y, a) in enumerate(zip(rng.uniform(-30, 30, 150).tolist(),
                                                rng.uniform(-30, 30, 150).tolist(),
                                                rng.uniform(-180, 180, 150).tolist(),
                                                strict=True))]
    edges = [(3.0, 3.0), (3.0, -3.0), (0.0, 4.0), (-2.0, 0.0), (5.0, 0.0)]
    targets += ['model( name "e%d" pose [ %r %r 0 0 ] size [ 0.2 0.2 0.5 ]'
                ' fiducial_return 1 )' % (k, x, y) for k, (x, y) in enumerate(edges)]
    finders = [('pose [ 0 0 0 0 ]', 'fov 90 range_max 5'),
               ('pose [ -8 -8 0 0 ]', 'fov 0 range_max 6'),
               ('pose [ 8 -8 0 90 ]', 'fov 180 range_max 4'),
               ('pose [ 1 2 0 -30 ]', 'fov 300 range_max 30'),
               ('pose [ -4 1 0 45 ]', 'fov 360 range_max 12')]
    body = '\n'.join('position( name "f%d" %s %s fiducial( %s ) )' % (k, ROBOT, pose, props)
                      for k, (pose, props) in enumerate(finders)) + '\n' + '\n'.join(targets)
    s = Scene(tmp_path, body)
    order = {m: float(r) for m, r in zip(s.index.models,
                                          rng.permutation(len(s.index.models)),
                                          strict=True)}
    s.index = FiducialIndex(s.world.models, rank=order.__getitem__)
    s.index.begin_step()
    layer = (s.world.updates + 1) % 2
    counts = []
    for k in range(len(finders)):
        f = s.finder(k)
        kernel = [(r.model.name, r.range, r.bearing, r.geom, r.pose, r.id)
                  for r in f.update(s.index, s.sight, layer)]
        rule = [(r.model.name, r.range, r.bearing, r.geom, r.pose, r.id)
                for r in f.update_one_by_one(s.index, s.sight, layer)]
        assert kernel == rule
        counts.append(len(kernel))
    names = [r.model.name for r in s.finder(0).update(s.index, s.sight, layer)]
    assert {'e0', 'e1'} <= set(names)          # on the fov's edges: seen
    assert 'e4' not in names                   # at range_max: not seen
    assert counts[1] == 0 and min(counts[3:]) > 10



def test_sights_rays_are_the_rangers_where_their_rules_agree(tmp_path):
    # every model seen by rangers, the beam at the finders' height: the same walk, the same hits
    s = Scene(tmp_path, 'define laser ranger ( sensor( range [ 0 6 ] fov 360 samples 721 ) )\n'
              'position( name "me" pose [ 0.13 -0.27 0 10 ] size [ 0.4 0.4 0.25 ] laser( ) )\n'
              'position( name "you" pose [ 1.5 1.1 0 0 ] size [ 0.5 0.3 0.5 ] )\n'
              'model( pose [ -2 0.3 0 25 ] size [ 0.3 2 1 ] )\n'
              'model( pose [ 0.4 -3.3 0 0 ] size [ 4 0.2 1 ] ranger_return 0 )\n'
              'model( pose [ 3.7 -1.1 0 60 ] size [ 1 1 0.4 ] )')
    w = s.world
    w.set_command(0, 0.3, 0.0, 0.4)
    w.set_command(1, -0.2, 0.0, -0.3)
    for _ in range(5):
        w.step()
    view = w.robots[0].rangers[0]
    origin = view.model.ray_origin(view.sensor)
    angles = np.empty(view.samples)
    raytrace.sample_angles(origin[3], Ranger.sample_increment(view.sensor), view.samples,
                           angles, 0)
    ranges, hits = s.sight.cast(origin, angles, view.range_max, view.model, True,
                                w.updates % 2)
    assert (hits >= 0).sum() > 300
    np.testing.assert_array_equal(ranges.astype(np.float32), view.ranges)
    rr = np.where(hits >= 0, w.space.model_rr[np.maximum(hits, 0)], 0.0)
    np.testing.assert_array_equal(rr.astype(np.float32), view.intensities)


def _g(x):
    return '%.17g' % x


@pytest.mark.parametrize('name', sorted(REAL_STAGE))
def test_every_digit_of_real_stages_first_readings(name):
    w = load_world(os.path.join(WORLDS, name))
    index = FiducialIndex(w.models)
    sight = Sight(w.models, w.robots, w.space)
    layer = (w.updates + 1) % 2
    index.begin_step()
    for robot, (blobs, fiducials) in REAL_STAGE[name].items():
        carried = next(m for m in w.models if m.name == robot).children
        eye = next(m for m in carried if m.kind == 'blobfinder')
        assert [' '.join([_g(c) for c in b.color[:3]] + [str(b.left), str(b.top), str(b.right),
                                                           str(b.bottom), _g(b.range)])
                for b in eye.update(sight, layer)] == blobs
        if fiducials is not None:
            finder = next(m for m in carried if m.kind == 'fiducial')
            readings = finder.update(index, sight, layer)
            assert [' '.join([r.model.name] + [_g(v) for v in (r.range, r.bearing) + r.geom]
                             + [str(r.id)]) for r in readings] == fiducials


def test_the_sets_sorted_again_from_the_last_order_are_numpys_stable_sort():
    """FiducialIndex.begin_step sorts the last step's orders again by insertion (fiducial
    _resort): the order np.lexsort gives, ties of coordinate and rank by place, from any
    starting order."""
    from stage_lite.model.fiducial import _resort
    gen = np.random.default_rng(3)
    for trial in range(200):
        n = int(gen.integers(1, 40))
        poses = gen.integers(-3, 4, (n, 4)).astype(np.float64) * 0.5    # many ties
        poses[gen.random(n) < 0.2, 0] = -0.0
        ranks = gen.integers(0, 6, n).astype(np.float64)                # some ties too
        for axis in (0, 1):
            order = gen.permutation(n).astype(np.int64)
            _resort(order, poses, axis, ranks)
            assert order.tolist() == np.lexsort((ranks, poses[:, axis])).tolist(), trial
