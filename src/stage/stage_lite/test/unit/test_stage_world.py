"""The World: loading, the collision rule, sensing by height, odometry, reset, bad worlds, and
the lesson's own geometry on the workspace's office plan."""
import math
import os
import subprocess
import sys

import pytest
from stage_lite.world import WorldError, load_world

HERE = os.path.dirname(os.path.abspath(__file__))
WORLD_DIR = os.path.join(HERE, '..', '..', 'world')
LESSON = os.path.join(WORLD_DIR, 'willow-multi-erratic.world')
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


# ---- the lesson's world on the workspace's own plan -----------------------------------------

@pytest.fixture(scope='module')
def lesson():
    return load_world(LESSON)


def test_lesson_world_figures(lesson):
    w = lesson
    assert [r.model_name for r in w.robots] == ['robot0', 'robot1', 'robot2', 'robot3']
    assert [r.start_pose for r in w.robots] == [(-11.5, 23.5, 0.0), (-13.5, 23.5, 0.0),
                                               (-11.5, 21.5, 0.0), (-13.5, 21.5, 0.0)]
    assert [r.color_rgb for r in w.robots] == [(0, 0, 1.0), (1.0, 0, 0), (0, 1.0, 0),
                                              (1.0, 0, 1.0)]
    g = w.robots[0].rangers[0]
    assert (g.samples, g.range_max, g.pose) == (1081, 30.0, (0.05, 0.0, 0.25, 0.0))
    assert g.angle_min == pytest.approx(-2.35838, abs=1e-5)
    assert g.angle_increment == pytest.approx(0.00436736, abs=1e-8)
    assert g.beam_z == pytest.approx(0.26)
    assert w.warnings == ['%s:40: property laser_return is defined but not used'
                          % os.path.normpath(LESSON)] or 'laser_return' in w.warnings[0]
    occ, ox, oy, res = w.occupancy()
    assert res == 0.02
    assert ox == pytest.approx(-58.74) and oy == pytest.approx(-0.04)
    assert occ.shape == (2704, 2939)


def test_lesson_drive_straight_front_pair_hits_wall_back_pair_hits_backs():
    w = load_world(LESSON)
    for i in range(4):
        w.set_command(i, 0.2, 0.0, 0.0)
    stalled_at = [None] * 4
    for k in range(200):
        w.step()
        for i, r in enumerate(w.robots):
            if r.stalled and stalled_at[i] is None:
                stalled_at[i] = k + 1
    travel = [r.pose[0] - r.start_pose[0] for r in w.robots]
    assert travel == pytest.approx([1.76, 3.38, 1.76, 3.38], abs=STEP_TOL)
    assert stalled_at == [89, 170, 89, 170]
    assert all(r.stalled for r in w.robots)
    # the lasers never see the other robots (bodies 0.25 m tall, beams at 0.26 m): the back
    # robot's laser, 0.05 m ahead of its pose, reads the wall face at -9.6 over the leader
    back = w.robots[1]
    assert back.rangers[0].ranges[540] == pytest.approx(-9.6 - (back.pose[0] + 0.05), abs=1e-5)


def test_lesson_scans_hit_walls(lesson):
    lesson.reset()
    lesson.step()
    for r in lesson.robots:
        g = r.rangers[0]
        assert g.ranges[540] == pytest.approx(-9.6 - (r.pose[0] + 0.05), abs=1e-6) \
            or r.start_pose[0] == -13.5
        assert (g.intensities == 1.0).mean() > 0.99


def test_floor_plan_script_reproduces_the_committed_pgm(tmp_path):
    out = tmp_path / 'office.pgm'
    subprocess.run([sys.executable, os.path.join(WORLD_DIR, 'draw_office.py'), str(out)],
                   check=True, capture_output=True)
    with open(os.path.join(WORLD_DIR, 'office.pgm'), 'rb') as f:
        assert out.read_bytes() == f.read()
