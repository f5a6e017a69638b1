"""Unit tests of turtle_lite.world: turtlesim's per-tick update (turtle.cpp's Turtle::update)."""

import math

import numpy as np
import pytest
from course_common.arena import SPAWN_M, WORLD_SIZE_M
from turtle_lite.world import (
    CMD_TIMEOUT_S,
    DEFAULT_PEN_RGB,
    DT_S,
    PI_TRUNC,
    World,
    turtlesim_wrap_angle,
)

F32 = 1e-6  # float32 pose fields: compare to about 1e-6


def f32(value):
    return float(np.float32(value))


def make_world(*turtles):
    world = World()
    for name, x, y, theta in turtles or [('turtle1', SPAWN_M, SPAWN_M, 0.0)]:
        world.add_turtle(name, x, y, theta)
    return world


def step_pose(world, now, name='turtle1'):
    result = world.step(now)
    return result.poses[result.names.index(name)], result


def test_constants_match_turtlesim():
    assert f32(WORLD_SIZE_M) == f32(11.08888912)
    assert f32(5.5444446) == SPAWN_M
    assert DT_S == 0.016
    assert PI_TRUNC == 3.14159265


def test_worked_trajectory_heading_first():
    world = make_world()
    x0 = SPAWN_M
    y0 = WORLD_SIZE_M - (WORLD_SIZE_M - SPAWN_M)
    for k in range(1, 250):
        world.set_command('turtle1', 1.0, 0.0, 0.5, now=0.0)
        pose, _ = step_pose(world, now=0.5)
        assert pose[2] == pytest.approx(0.008 * k, abs=F32)
        xk = x0 + 0.016 * sum(math.cos(0.008 * i) for i in range(1, k + 1))
        yk = y0 + 0.016 * sum(math.sin(0.008 * i) for i in range(1, k + 1))
        assert pose[0] == pytest.approx(xk, abs=F32)
        assert pose[1] == pytest.approx(yk, abs=F32)
    # The real node's end point after its 249 moving ticks.
    assert pose[0] == pytest.approx(7.358359, abs=2e-6)
    assert pose[1] == pytest.approx(8.369450, abs=2e-6)


@pytest.mark.parametrize('theta, expected', [
    (f32(math.pi), -3.1415925),
    (-f32(math.pi), 3.1415925),
    (3.5, -2.7831852),
    (7.0, 0.7168147),
    (0.0, 0.0),
    (-PI_TRUNC, -PI_TRUNC),
    (PI_TRUNC, -PI_TRUNC),
])
def test_turtlesim_wrap_angle_truncated_pi(theta, expected):
    assert f32(turtlesim_wrap_angle(theta)) == pytest.approx(expected, abs=2e-7)


@pytest.mark.parametrize('theta', [1e12, -1e12, 3e38, -3e38, 1e300])
def test_turtlesim_wrap_angle_huge_values_stay_in_range(theta):
    out = turtlesim_wrap_angle(theta)
    assert -PI_TRUNC <= out < PI_TRUNC


def test_turtlesim_wrap_angle_arrays():
    out = turtlesim_wrap_angle(np.array([3.5, 7.0, -7.0]))
    assert out == pytest.approx([3.5 - 2 * PI_TRUNC, 7.0 - 2 * PI_TRUNC, -7.0 + 2 * PI_TRUNC])


def test_teleport_theta_pi_published_wrapped():
    world = make_world()
    world.teleport_absolute('turtle1', 1.0, 1.0, math.pi)
    pose, _ = step_pose(world, 0.0)
    assert f32(pose[2]) == pytest.approx(-3.1415925, abs=2e-7)


def test_fresh_turtle_is_stationary():
    world = make_world()
    for _ in range(5):
        pose, _ = step_pose(world, now=100.0)
    assert tuple(pose) == pytest.approx((SPAWN_M, SPAWN_M, 0.0, 0.0, 0.0), abs=F32)


def test_timeout_stops_after_one_second_and_zeroes_velocities():
    world = make_world()
    world.set_command('turtle1', 1.0, 0.0, 0.0, now=10.0)
    pose, _ = step_pose(world, 10.0 + CMD_TIMEOUT_S)  # exactly 1 s: still moving
    assert pose[3] == 1.0
    x_before = pose[0]
    pose, _ = step_pose(world, 10.0 + CMD_TIMEOUT_S + 0.001)
    assert pose[0] == x_before  # motion stops on the same tick ...
    assert pose[3] == 0.0 and pose[4] == 0.0  # ... as the velocities drop to 0


def test_teleports_do_not_reset_velocities_or_timer():
    world = make_world()
    world.set_command('turtle1', 1.0, 0.0, 0.5, now=0.0)
    world.teleport_absolute('turtle1', 2.0, 2.0, 0.0)
    pose, _ = step_pose(world, 0.5)
    assert pose[3] == 1.0 and pose[4] == 0.5
    pose, _ = step_pose(world, 1.5)  # the teleport did not refresh the timer
    assert pose[3] == 0.0


@pytest.mark.parametrize('vx, vy, expected', [(-1.0, 0.0, 1.0), (3.0, 4.0, 5.0),
                                              (0.0, -2.0, 2.0)])
def test_linear_velocity_is_hypot(vx, vy, expected):
    world = make_world()
    world.set_command('turtle1', vx, vy, -0.7, now=0.0)
    pose, _ = step_pose(world, 0.1)
    assert pose[3] == pytest.approx(expected)
    assert pose[4] == pytest.approx(-0.7)


def test_holonomic_y_moves_left():
    world = make_world()
    world.set_command('turtle1', 0.0, 1.0, 0.0, now=0.0)
    pose, _ = step_pose(world, 0.1)
    assert pose[0] == pytest.approx(SPAWN_M, abs=F32)
    assert pose[1] == pytest.approx(SPAWN_M + 0.016, abs=F32)
    world.teleport_absolute('turtle1', 5.0, 5.0, math.pi / 2)  # facing +y, left is -x
    world.set_command('turtle1', 0.0, 1.0, 0.0, now=0.0)
    pose, _ = step_pose(world, 0.1)
    assert pose[0] == pytest.approx(5.0 - 0.016, abs=F32)


def test_wall_hits_report_screen_y_and_clamp_without_zeroing_velocity():
    world = make_world(('turtle1', 0.01, 0.01, 0.0))
    world.set_command('turtle1', -1.0, 0.0, 0.0, now=0.0)  # backwards into x = 0
    pose, result = step_pose(world, 0.1)
    assert len(result.wall_hits) == 1
    hit = result.wall_hits[0]
    assert hit.name == 'turtle1'
    assert hit.x == pytest.approx(f32(0.01) - 0.016)
    assert hit.y_s == pytest.approx(WORLD_SIZE_M - f32(0.01))
    assert pose[0] == 0.0
    assert pose[3] == 1.0  # still the commanded speed
    _, result = step_pose(world, 0.2)
    assert len(result.wall_hits) == 1  # one warning per tick while pushing


def test_sitting_exactly_on_wall_does_not_warn():
    world = make_world(('turtle1', 0.0, 0.0, 0.0))
    _, result = step_pose(world, 0.1)
    assert result.wall_hits == []
    world.teleport_absolute('turtle1', 0.0, WORLD_SIZE_M, 0.0)  # float32(H) > H: a wall hit
    _, result = step_pose(world, 0.1)
    assert len(result.wall_hits) == 0  # the top edge is clamped silently by the teleport


def test_spawn_out_of_range_clamped_on_first_step():
    world = make_world(('t', -2.0, 20.0, 7.0))
    pose, result = step_pose(world, 0.0, name='t')
    assert [(h.x, round(h.y_s, 6)) for h in result.wall_hits] == [(-2.0, -8.911111)]
    assert pose[0] == 0.0
    assert pose[1] == pytest.approx(11.088889, abs=F32)
    assert pose[2] == pytest.approx(0.7168147, abs=2e-7)


def test_teleport_absolute_above_top_clamps_silently_but_below_bottom_warns():
    world = make_world()
    world.teleport_absolute('turtle1', 3.0, 50.0, 0.0)
    pose, result = step_pose(world, 0.0)
    assert result.wall_hits == []
    assert pose[1] == pytest.approx(WORLD_SIZE_M, abs=F32)
    world.teleport_absolute('turtle1', 3.0, -1.0, 0.0)
    pose, result = step_pose(world, 0.0)
    assert len(result.wall_hits) == 1
    assert pose[1] == 0.0


def test_teleports_are_queued_in_order_and_relative_rotates_first():
    world = make_world()
    world.teleport_absolute('turtle1', 2.0, 2.0, 0.0)
    world.teleport_relative('turtle1', 1.0, math.pi / 2)  # turn left, then 1 m "up"
    assert world.pose('turtle1').x == pytest.approx(SPAWN_M)  # nothing before the step
    pose, _ = step_pose(world, 0.0)
    assert pose[0] == pytest.approx(2.0, abs=F32)
    assert pose[1] == pytest.approx(3.0, abs=F32)
    assert pose[2] == pytest.approx(math.pi / 2, abs=F32)


def test_teleport_draws_line_so_sensor_reads_pen():
    world = make_world()
    _, result = step_pose(world, 0.0)
    assert tuple(result.colors[0]) == (69, 86, 255)
    world.teleport_absolute('turtle1', 2.0, 2.0, 0.0)
    _, result = step_pose(world, 0.0)
    assert tuple(result.colors[0]) == DEFAULT_PEN_RGB


def test_stopped_on_own_trail_reads_pen_colour():
    world = make_world()
    world.set_command('turtle1', 1.0, 0.0, 0.0, now=0.0)
    for _ in range(20):
        world.step(0.5)
    _, result = step_pose(world, 5.0)  # timed out: stopped on its trail
    assert tuple(result.colors[0]) == DEFAULT_PEN_RGB


def test_set_pen_rules():
    world = make_world()
    assert world.pen('turtle1') == (True, DEFAULT_PEN_RGB, 3)
    world.set_pen('turtle1', 255, 0, 0, 0, 0)
    assert world.pen('turtle1') == (True, (255, 0, 0), 1)  # width 0 means 1 px
    world.set_pen('turtle1', 1, 2, 3, 9, 1)
    assert world.pen('turtle1') == (False, (255, 0, 0), 1)  # off keeps colour and width
    world.set_pen('turtle1', 0, 255, 0, 7, 0)
    assert world.pen('turtle1') == (True, (0, 255, 0), 7)


def test_pen_off_draws_nothing():
    world = make_world()
    world.set_pen('turtle1', 0, 0, 0, 3, 1)
    world.teleport_absolute('turtle1', 1.0, 1.0, 0.0)
    world.step(0.0)
    assert (world.canvas.pixels == (69, 86, 255)).all()


def test_clear_keeps_turtles_and_pens():
    world = make_world()
    world.set_pen('turtle1', 10, 20, 30, 5, 0)
    world.teleport_absolute('turtle1', 1.0, 1.0, 0.0)
    world.step(0.0)
    world.clear((1, 2, 3))
    assert (world.canvas.pixels == (1, 2, 3)).all()
    assert world.pen('turtle1') == (True, (10, 20, 30), 5)
    _, result = step_pose(world, 0.0)
    assert tuple(result.colors[0]) == (1, 2, 3)


def test_turtles_in_name_order_and_duplicates_rejected():
    world = make_world(('b', 1, 1, 0), ('a', 2, 2, 0), ('c', 3, 3, 0))
    assert world.step(0.0).names == ('a', 'b', 'c')
    with pytest.raises(ValueError, match=r'A turtled named \[a\] already exists'):
        world.add_turtle('a', 0, 0, 0)
    world.remove_turtle('b')
    assert world.step(0.0).names == ('a', 'c')
    with pytest.raises(KeyError, match='Tried to kill turtle'):
        world.remove_turtle('b')


def test_wall_hits_in_name_order():
    world = make_world(('zeta', -1, 1, 0), ('alpha', -1, 1, 0))
    assert [h.name for h in world.step(0.0).wall_hits] == ['alpha', 'zeta']


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf, 1e300])
def test_non_finite_commands_rejected_and_turtle_intact(bad):
    world = make_world()
    world.set_command('turtle1', 1.0, 0.0, 0.0, now=0.0)
    with pytest.raises(ValueError):
        world.set_command('turtle1', bad, 0.0, 0.0, now=0.0)
    with pytest.raises(ValueError):
        world.teleport_absolute('turtle1', 1.0, bad, 0.0)
    with pytest.raises(ValueError):
        world.teleport_relative('turtle1', 0.0, bad)
    with pytest.raises(ValueError):
        world.add_turtle('t2', bad, 1.0, 0.0)
    pose, _ = step_pose(world, 0.1)
    assert np.isfinite(pose).all()
    assert pose[3] == 1.0
    assert 't2' not in world


def test_absurd_but_finite_values_clamp_and_stay_finite():
    world = make_world()
    world.teleport_absolute('turtle1', 3e38, -3e38, 3e38)
    world.teleport_relative('turtle1', 1e15, 1e15)
    world.set_command('turtle1', 1e15, -1e15, 1e15, now=0.0)
    for _ in range(3):
        pose, result = step_pose(world, 0.1)
        assert np.isfinite(pose).all()
        assert 0.0 <= pose[0] <= f32(WORLD_SIZE_M)
        assert 0.0 <= pose[1] <= f32(WORLD_SIZE_M)
        assert -PI_TRUNC <= pose[2] <= PI_TRUNC


def test_idle_step_reuses_results_but_sees_canvas_changes():
    world = make_world()
    first = world.step(0.0)
    again = world.step(0.0)
    assert again.poses is first.poses
    world.clear((9, 9, 9))
    assert tuple(world.step(0.0).colors[0]) == (9, 9, 9)
