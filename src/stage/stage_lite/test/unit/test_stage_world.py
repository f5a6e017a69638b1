"""The World as Stage steps it (stage_lite.model.world): when commands take effect, moves and
stalls, odometry, reset, drives, update intervals, and the worlds Stage refuses or warns about.

Beam-by-beam and pose-by-pose agreement with real Stage is test_stage_golden.py's; these
tests state the rules one at a time on small worlds."""
import math

import numpy as np
import pytest
from stage_lite.model.pose import pose_add, stage_normalize
from stage_lite.model.world import WorldError, load_world
from stage_lite.testing.room import write_room_pgm

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
    """A 10 m square room (0.1 m walls), robot a at the origin facing +x and robot b at
    (bx, 0) facing it."""
    write_room_pgm(str(tmp_path / 'room.pgm'))
    p = tmp_path / 'room.world'
    p.write_text(ROOM % dict(h=h, hb=hb, bx=bx, drive=drive, extra=extra))
    return load_world(str(p), seed=3)


def run(w, steps):
    for _ in range(steps):
        w.step()


def test_load_and_scan_fields(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    a = w.robots[0]
    assert (w.interval_sim_s, w.resolution_m, w.sim_time_us) == (0.1, 0.02, 0)
    assert a.rangers[0].angle_increment == pytest.approx(math.pi / 180)
    assert not a.rangers[0].has_data      # stageros publishes a ranger after its first update
    w.step()
    g = a.rangers[0]
    assert g.has_data and w.sim_time_us == 100_000
    assert g.ranges[90] == pytest.approx(4.9, abs=0.02)      # straight ahead to the wall
    assert g.intensities.tolist() == [1.0] * 181


@pytest.mark.parametrize('hb, seen', [(0.25, False), (0.5, True), (0.1, False)])
def test_other_robot_seen_only_when_its_height_holds_the_beam(tmp_path, hb, seen):
    w = room_world(tmp_path, hb=hb)      # beam at 0.25 + 0.01; b's body from 0 to hb
    w.step()
    ahead = w.robots[0].rangers[0].ranges[90]
    assert ahead == pytest.approx(1.8 if seen else 4.9, abs=0.02)


def test_a_command_moves_the_robot_from_the_next_step(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    a = w.robots[0]
    w.set_command(0, 0.5, 0.3, 0.2)     # diff: vy ignored
    assert a.command == (0.0, 0.0, 0.0)  # the goal waits for the robot's update
    w.step()
    assert a.command == (0.5, 0.0, 0.2)
    # Stage's move: translation turned by the OLD heading, then the turn
    assert (a.pose[0], a.pose[1]) == (0.05, 0.0) and a.pose[2] == 0.2 * 0.1
    assert a.truth_twist == pytest.approx((0.5, 0.0, 0.2), abs=1e-9)


def test_gps_odometry_is_the_pose_before_the_step(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    a = w.robots[0]
    w.set_command(0, 0.5, 0.0, 0.3)
    poses = []
    for _ in range(4):
        w.step()
        poses.append(a.pose)
    # the estimate is taken at the robot's update, before this step's move
    assert a.odom_pose == poses[-2] and a.odom_pose != a.pose


def test_odom_localisation_integrates_from_zero_with_stage_signs(tmp_path):
    w = room_world(tmp_path, bx=-3.0, drive='omni',
                   extra='localization "odom" odom_error [0.1 0.2 0 10]')
    a = w.robots[0]
    assert a.odom_pose == (0.0, 0.0, 0.0)
    w.set_command(0, 0.4, 0.3, 0.5)
    w.step()
    dt, ex, ey, ea = 0.1, 0.1, 0.2, 10 * math.pi / 180
    yaw = stage_normalize(0.0 + (0.5 * dt) * (1 + ea))
    dx, dy = (0.4 * dt) * (1 + ex), (0.3 * dt) * (1 + ey)
    # Stage subtracts dy * cos - dx * sin from y: a y velocity drifts the other way
    expected = (dx * math.cos(yaw) + dy * math.sin(yaw), -(dy * math.cos(yaw)
                                                          - dx * math.sin(yaw)), yaw)
    assert a.odom_pose == expected
    x, y, _, yaw = pose_add((0.0, 0.0, 0.0, 0.0), (0.4 * dt, 0.3 * dt, 0.0, 0.5 * dt))
    assert a.pose == (x, y, yaw)


def test_collision_undoes_whole_step_and_keeps_command(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    a = w.robots[0]
    w.set_command(0, 1.0, 0.0, 0.0)
    run(w, 60)
    # stops with its front within one 0.1 m step of the wall face at 4.9
    assert a.stalled and 4.9 - 0.12 <= a.pose[0] + 0.2 <= 4.9
    assert a.command == (1.0, 0.0, 0.0) and a.truth_twist == (0.0, 0.0, 0.0)
    x = a.pose[0]
    w.set_command(0, 0.0, 0.0, 1.0)      # turning here would swing a corner into the wall
    w.step()
    assert a.stalled and a.pose == (x, 0.0, 0.0)
    w.set_command(0, -1.0, 0.0, 0.0)     # backing away is free: un-stalls
    w.step()
    assert not a.stalled and a.pose[0] == pytest.approx(x - 0.1, abs=1e-9)


def test_robots_stall_against_each_other(tmp_path):
    w = room_world(tmp_path, bx=1.0)
    w.set_command(0, 0.2, 0.0, 0.0)
    run(w, 40)
    a, b = w.robots
    gap = (b.pose[0] - 0.2) - (a.pose[0] + 0.2)
    assert a.stalled and 0.0 < gap < 0.06 and b.pose[0] == 1.0 and not b.stalled


def test_reset_restores_poses_and_keeps_what_stage_keeps(tmp_path):
    w = room_world(tmp_path, bx=-3.0, extra='localization "odom"')
    a = w.robots[0]
    w.set_command(0, 0.5, 0.0, 0.2)
    run(w, 3)
    est = a.odom_pose
    a.stalled = True
    w.reset()
    # stageros's reset_positions: SetPose to the start and SetStall(false); the goal, the
    # velocity and the odometry estimate stay
    assert (a.pose, a.stalled) == ((0.0, 0.0, 0.0), False)
    assert a.command == (0.5, 0.0, 0.2) and a.odom_pose == est
    w.step()
    assert a.pose != (0.0, 0.0, 0.0)


def test_watchdog_stop_zeroes_the_goal(tmp_path):
    w = room_world(tmp_path, bx=-3.0)
    a = w.robots[0]
    w.set_command(0, 0.5, 0.0, 0.0)
    w.step()
    w.stop_all()
    assert a.command == (0.5, 0.0, 0.0)    # this step's velocity, shown in this step's odom
    w.step()
    assert a.command == (0.0, 0.0, 0.0)


def test_goto_drives_at_the_c_librarys_hypot_of_the_error(tmp_path):
    # Stage's position control: vx = min(hypot(y_err, x_err), 0.4), hypot the C library's.
    # For this error Python's math.hypot gives the float next to it.
    x, y = 0.117, 0.006
    assert math.hypot(y, x) != np.hypot(y, x)
    w = room_world(tmp_path, bx=-3.0)
    w.handle(w.robots[0].model).go_to(x, y, 0.0)
    w.step()
    assert w.robots[0].command[0] == np.hypot(y, x)


def test_a_sensor_keeps_its_angle_as_written_and_a_model_its_pose_normalised(tmp_path):
    # Stage's Pose::Load calls normalize(a) and drops what it returns: a sensor's (and a
    # body's origin's) angle stays as written, 330 degrees, whose sine differs from -30
    # degrees' in the last bit; Model::Load's SetPose normalises the model's own pose
    p = tmp_path / 'w.world'
    p.write_text('resolution 0.02\n'
                 'position( pose [ 0 0 0 330 ] origin [ 0 0 0 270 ] size [ 0.2 0.2 0.2 ]\n'
                 '  ranger( sensor( pose [ 0 0 0 330 ] range [ 0 2 ] fov 30 samples 1 ) ) )\n')
    w = load_world(str(p))
    a = 330 * (math.pi / 180.0)
    robot = w.robots[0]
    assert robot.ranger_models[0].sensors[0].pose[3] == a
    assert robot.model.geom_pose[3] == 270 * (math.pi / 180.0)
    assert robot.model.pose[3] == stage_normalize(a) != a
    assert math.sin(a) != math.sin(stage_normalize(a))


def test_car_drive_steers_with_angular_z(tmp_path):
    w = room_world(tmp_path, bx=-3.0, drive='car', extra='wheelbase 0.5')
    w.set_command(0, 0.4, 0.0, 0.3)
    w.step()
    vx, vy, wz = w.robots[0].command
    assert (vx, vy, wz) == (0.4 * math.cos(0.3), 0.0, 0.4 * math.sin(0.3) / 0.5)


def test_velocity_bounds_clamp(tmp_path):
    w = room_world(tmp_path, bx=-3.0, extra='velocity_bounds [-0.1 0.2 -1 1 -1 1 -30 30]')
    w.set_command(0, 5.0, 0.0, -3.0)
    w.step()
    assert w.robots[0].command == (0.2, 0.0, -30 * math.pi / 180)


def test_update_interval_spaces_the_robots_updates(tmp_path):
    w = room_world(tmp_path, bx=-3.0, extra='update_interval 300')
    a = w.robots[0]
    w.set_command(0, 0.5, 0.0, 0.0)
    seen = []
    for _ in range(7):
        w.step()
        seen.append(a.command[0])
    # the first update at 300 ms, then every 300 ms; the robot moves at every step
    assert seen == [0.0, 0.0, 0.5, 0.5, 0.5, 0.5, 0.5]
    assert a.pose[0] == pytest.approx(0.25, abs=1e-12)


@pytest.mark.parametrize('bad', [math.nan, math.inf])
def test_non_finite_command_refused(tmp_path, bad):
    w = room_world(tmp_path)
    with pytest.raises(ValueError):
        w.set_command(0, bad, 0.0, 0.0)
    assert w.robots[0].goal == (0.0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize('text, line, what', [
    ('model( bitmap "none.pgm" )', 1, 'none.pgm: bitmap file does not exist'),
    ('\nmodel( bitmap "room.world" )', 2, 'not an image'),
    ('resolution 0', 1, 'resolution must be > 0'),
    ('position( ranger( sensor( samples 0 ) ) )', 1, 'samples must be at least 1'),
    ('walle( )', 1, 'unknown model type "walle"'),
    ('model( pose [ 1 2 45 ] )', 1, 'pose needs 4 values, got 3'),
    ('sensor( )', 1, 'sensor( ) belongs inside a ranger'),
    ('block( points 0 )', 1, 'block( ) belongs inside a model'),
])
def test_what_stage_refuses(tmp_path, text, line, what):
    p = tmp_path / 'room.world'
    p.write_text(text)
    with pytest.raises(WorldError) as e:
        load_world(str(p))
    assert str(e.value).startswith('%s:%d:' % (p, line)) and what in str(e.value)


def test_missing_world(tmp_path):
    with pytest.raises(WorldError, match='does not exist'):
        load_world(str(tmp_path / 'none.world'))


@pytest.mark.parametrize('text, warning', [
    ('model( color "octarine" )', 'unknown colour "octarine"; Stage uses red'),
    ('position( drive "tank" )', 'invalid drive "tank"'),
    ('position( localization "slam" )', 'unknown localization "slam"'),
    ('threads 0', 'threads set to <1. Forcing to 1'),
    ('camera( )', 'camera camera:0 is not on a position model: stageros publishes nothing'),
    ('gripper( )', 'gripper models are not simulated here'),
    ('model( laser_return 1 )', 'property laser_return is defined but not used'),
])
def test_what_stage_accepts_with_a_warning(tmp_path, text, warning):
    p = tmp_path / 'w.world'
    p.write_text(text)
    w = load_world(str(p))
    assert any(warning in m for m in w.warnings), w.warnings


def test_stage_leniency_loads(tmp_path):
    p = tmp_path / 'w.world'
    p.write_text('speedup 0\nthreads 2\nposition( odom_error [0.1 0.1 0 0.1 0 0] drive "tank"'
                 ' color "octarine" )')
    w = load_world(str(p))
    r = w.robots[0]
    assert (w.speedup, r.drive, r.color_rgb) == (0.0, 'diff', (1.0, 0.0, 0.0))


def test_a_robot_driving_far_out_grows_the_grid(tmp_path):
    p = tmp_path / 'w.world'
    p.write_text('resolution 0.02\nmodel( pose [ 0 2 0 0 ] size [ 1 0.2 0.5 ] )\n'
                 'position( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.2 ]'
                 ' ranger( sensor( range [ 0 5 ] fov 90 samples 3 ) ) )\n'
                 'position( pose [ 0 -1 0 0 ] size [ 0.3 0.3 0.2 ] )')
    w = load_world(str(p))
    w.set_command(0, 1.0, 0.0, 0.0)
    run(w, 600)                      # 60 m east, far past the grid made at the load
    a = w.robots[0]
    assert a.pose[0] == pytest.approx(60.0, abs=1e-6) and not a.stalled
    assert a.rangers[0].ranges.tolist() == [5.0, 5.0, 5.0]
    w.set_command(0, -1.0, 0.0, 0.0)
    run(w, 600)                      # and back
    assert a.pose[0] == pytest.approx(0.0, abs=1e-6)
    w.set_command(0, 0.0, 0.0, math.pi / 2)
    run(w, 10)                       # a quarter turn: facing the wall 2 m north
    w.set_command(0, 0.0, 0.0, 0.0)
    run(w, 2)
    assert a.rangers[0].ranges[1] == pytest.approx(1.9, abs=0.03)


@pytest.mark.parametrize('text, robots', [
    ('model( size [ 1 1 1 ] )', 0),                       # no robot
    ('position( )\nposition( pose [ 2 0 0 0 ] )', 2),     # robots only, no laser
    ('', 0),                                              # nothing at all
])
def test_sparse_worlds_step(tmp_path, text, robots):
    p = tmp_path / 'w.world'
    p.write_text(text)
    w = load_world(str(p))
    assert len(w.robots) == robots
    for i in range(robots):
        w.set_command(i, 0.3, 0.0, 0.1)
    run(w, 5)
    assert w.sim_time_us == 500_000
    occ, _, _, _ = w.occupancy()
    assert occ.ndim == 2
