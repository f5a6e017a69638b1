"""The lesson's world on the workspace's own office plan, loaded by stage_lite's model: its
figures, the drive into the wall (where the front and the back pair stall), the scans, and the
floor plan's script reproducing the committed office.pgm.

Moved here with world/ from stage_lite's test_stage_world.py; stage_lite's own tests need no
lesson."""
import os
import subprocess
import sys

import pytest
from stage_lite.world import load_world

HERE = os.path.dirname(os.path.abspath(__file__))
WORLD_DIR = os.path.join(HERE, '..', '..', 'world')
LESSON = os.path.join(WORLD_DIR, 'willow-multi-erratic.world')
STEP_TOL = 1e-9      # m: poses are sums of exact 2 cm steps


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
