"""The lesson's world on the workspace's own office plan, loaded by stage_lite's model: its
figures, the drive into the wall held to real Stage 4.3.0 step by step (golden data of the
lesson's own drive, ../golden/lesson_drive.npz), and the floor plan's script reproducing the
committed office.pgm.

Moved here with world/ from stage_lite's test_stage_world.py; stage_lite's own tests need no
lesson."""
import os
import subprocess
import sys

import pytest
from stage_lite.model.world import load_world
from stage_lite.testing import golden

HERE = os.path.dirname(os.path.abspath(__file__))
WORLD_DIR = os.path.join(HERE, '..', '..', 'world')
LESSON = os.path.join(WORLD_DIR, 'willow-multi-erratic.world')
GOLDEN = os.path.join(HERE, '..', 'golden', 'lesson_drive.npz')
STEP_TOL = 1e-9      # m: poses are sums of 2 cm steps
# Real Stage 4.3.0 on this world (the golden capture): all four at 0.2 m/s, the front pair
# stalls at the hall's east wall after 1.74 m, at its 88th step, the back pair behind them
# after 3.36 m, at its 169th (the back robots' lasers, at 0.26 m, pass above the others)
TRAVEL_M = [1.74, 3.36, 1.74, 3.36]
STALL_STEP = [88, 169, 88, 169]


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
                          % os.path.normpath(LESSON)]
    occ, ox, oy, res = w.occupancy()
    assert res == 0.02 and occ.any()
    # the floor plan covers x in [-58.7, 0], y in [0, 54]
    assert ox == pytest.approx(-58.74, abs=0.03) and oy == pytest.approx(-0.04, abs=0.03)


def test_lesson_drive_front_pair_at_the_wall_back_pair_behind_them():
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
    assert travel == pytest.approx(TRAVEL_M, abs=STEP_TOL)
    assert stalled_at == STALL_STEP
    assert all(r.stalled for r in w.robots)


def test_lesson_drive_equals_real_stage_step_by_step():
    gold, meta = golden.load(GOLDEN)
    assert meta['world'] == os.path.basename(LESSON)
    frames = golden.replay(LESSON, gold, meta)
    golden.check_poses(gold, frames)
    golden.check_stalls(gold, frames)
    compared, _ = golden.check_scans(gold, frames)
    assert compared == 4 * len(frames)


def test_floor_plan_script_reproduces_the_committed_pgm(tmp_path):
    out = tmp_path / 'office.pgm'
    subprocess.run([sys.executable, os.path.join(WORLD_DIR, 'draw_office.py'), str(out)],
                   check=True, capture_output=True)
    with open(os.path.join(WORLD_DIR, 'office.pgm'), 'rb') as f:
        assert out.read_bytes() == f.read()
