"""The World: loading, the collision rule, sensing by height, odometry, reset, bad worlds.

The lesson's own world and floor plan live in stage_multi, and so do their tests
(stage_multi's test/unit/test_lesson_world.py)."""
import math

import pytest
from stage_lite.world import WorldError, load_world

STEP_TOL = 1e-9      # m: poses are sums of exact 2 cm steps

ROOM = '''resolution 0.02
interval_sim 100
define box model ( size [10 10 1] bitmap "room.pgm" )
define bot position ( size [0.4 0.4 %(h)s] drive "%(drive)s"
  ranger( sensor( range [0 20] fov 180 samples 181 ) ) )
box( pose [0 0 0 0] name "room" )
bot( pose [0 0 0 0] name "a" color "blue" %(extra)s )
bot( pose [%(bx)s 0 0 180] name "b" color "gray30" size [0.4 0.4 %(hb)s] )
'''


def room_world(tmp_path, h=0.25, hb=0.25, bx=2.0, drive='diff', extra=''):
    """A 10 m square room, free inside [-4.9, 4.9] (0.1 m walls), robot a at the origin facing
    +x and robot b at (bx, 0) facing it."""
    n = 100
    img = bytearray(b'\xff' * n * n)
    for i in range(n):
        for j in (0, n - 1):
            img[i * n + j] = img[j * n + i] = 0
    (tmp_path / 'room.pgm').write_bytes(b'P5 %d %d 255\n' % (n, n) + bytes(img))
    p = tmp_path / 'room.world'
    p.write_text(ROOM % dict(h=h, hb=hb, bx=bx, drive=drive, extra=extra))
    return load_world(str(p), seed=3)


def test_load_and_scan_fields(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    a = w.robots[0]
    assert (w.interval_sim_s, w.resolution_m) == (0.1, 0.02)
    assert a.rangers[0].angle_increment == pytest.approx(math.pi / 180)
    w.step()
    g = a.rangers[0]
    assert g.ranges[90] == pytest.approx(4.9, abs=1e-6)      # straight ahead to the wall
    assert g.ranges[0] == pytest.approx(4.9, abs=1e-6)
    assert g.intensities.tolist() == [1.0] * 181
    assert w.sim_time_s == pytest.approx(0.1)


@pytest.mark.parametrize('hb, seen', [(0.25, False), (0.5, True), (0.1, False)])
def test_other_robot_seen_only_when_its_height_holds_the_beam(tmp_path, hb, seen):
    w = room_world(tmp_path, hb=hb)      # beam at 0.25 + 0.01; b's body from 0 to hb
    w.step()
    ahead = w.robots[0].rangers[0].ranges[90]
    assert ahead == pytest.approx(2.0 - 0.2 if seen else 4.9, abs=1e-6)


def test_collision_undoes_whole_step_and_keeps_command(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    w.set_command(0, 1.0, 0.0, 0.0)
    for _ in range(60):
        w.step()
    a = w.robots[0]
    # stops with its front within one 0.1 m step of the wall face at 4.9
    assert a.stalled and 4.9 - 0.1 <= a.pose[0] + 0.2 <= 4.9
    assert a.pose[0] == pytest.approx(round(a.pose[0], 1), abs=STEP_TOL)
    assert a.command == (1.0, 0.0, 0.0) and a.truth_twist == (0.0, 0.0, 0.0)
    x = a.pose[0]
    w.set_command(0, 0.0, 0.0, 1.0)      # turning here would swing a corner into the wall
    w.step()
    assert a.stalled and a.pose == (x, 0.0, 0.0)
    w.set_command(0, -1.0, 0.0, 0.0)     # backing away is free: un-stalls
    w.step()
    assert not a.stalled and a.pose[0] == pytest.approx(x - 0.1, abs=STEP_TOL)


def test_robots_stop_one_cell_apart(tmp_path):
    w = room_world(tmp_path, bx=1.0)
    w.set_command(0, 0.2, 0.0, 0.0)
    for _ in range(40):
        w.step()
    a, b = w.robots
    gap = (b.pose[0] - 0.2) - (a.pose[0] + 0.2)
    assert a.stalled and 0.02 <= gap < 0.04 and b.pose[0] == 1.0


def test_reset_and_truth_twist(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    w.set_command(0, 0.5, 0.3, 0.2)     # diff: vy ignored
    w.step()
    a = w.robots[0]
    assert a.command == (0.5, 0.0, 0.2)
    assert a.truth_twist == pytest.approx((0.5, 0.0, 0.2), abs=1e-9)
    assert a.odom_pose == a.pose        # localization gps: odometry is the world pose
    w.reset()
    assert (a.pose, a.stalled, a.command) == ((0.0, 0.0, 0.0), False, (0.0, 0.0, 0.0))


def test_odom_drifts_seeded(tmp_path):
    w = room_world(tmp_path, bx=-3.0, extra='localization "odom" odom_error [0.2 0.2 0 0.2]')
    w.set_command(0, 0.5, 0.0, 0.0)
    for _ in range(5):
        w.step()
    a = w.robots[0]
    ex = a.odom_error_drawn[0]
    assert abs(ex) <= 0.1 and ex != 0
    assert a.odom_pose[0] == pytest.approx(a.pose[0] * (1 + ex), abs=1e-9)
    again = room_world(tmp_path, bx=-3.0,
                       extra='localization "odom" odom_error [0.2 0.2 0 0.2]')
    assert again.robots[0].odom_error_drawn == a.odom_error_drawn


@pytest.mark.parametrize('bad', [math.nan, math.inf])
def test_non_finite_command_refused(tmp_path, bad):
    w = room_world(tmp_path)
    with pytest.raises(ValueError):
        w.set_command(0, bad, 0.0, 0.0)
    assert w.robots[0].command == (0.0, 0.0, 0.0)


@pytest.mark.parametrize('text, what', [
    ('model( bitmap "none.pgm" )', 'none.pgm: bitmap file does not exist'),
    ('model( bitmap "room.world" )', 'not an image'),
    ('position( drive "tank" )', 'drive must be'),
    ('resolution 0', 'resolution must be > 0'),
    ('position( ranger( sensor( samples 0 ) ) )', 'samples must be'),
    ('walle( )', 'unknown model type'),
])
def test_bad_worlds(tmp_path, text, what):
    p = tmp_path / 'room.world'
    p.write_text(text)
    with pytest.raises(WorldError) as e:
        load_world(str(p))
    assert str(e.value).startswith(str(p) + ':') and what in str(e.value)


def test_missing_world(tmp_path):
    with pytest.raises(WorldError, match='does not exist'):
        load_world(str(tmp_path / 'none.world'))


def test_unknown_colour_warns(tmp_path):
    p = tmp_path / 'w.world'
    p.write_text('model( color "octarine" size [1 1 1] pose [5 5 0 0] )')
    w = load_world(str(p))
    assert w.models[0].color_rgb == (1.0, 0.0, 0.0)
    assert any('unknown colour "octarine"' in m for m in w.warnings)
