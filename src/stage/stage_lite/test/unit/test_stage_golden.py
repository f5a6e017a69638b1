"""stage_lite held to real Stage 4.3.0 + stage_ros 1.8.0, step by step and beam by beam.

The golden data (../golden/data/*.npz) are captures of real Stage, built from source, on the
workspace's own worlds (../golden/worlds/: a turned floor plan with thin, diagonal and grey
walls at negative coordinates; bodies of every kind with robots of every drive; one floor
plan per image format) and on the synchronisation lesson's world (stage_multi's, embedded in
its capture: this package depends on no lesson), made as ../golden/README.md says.
stage_lite.testing.golden replays each in stage_lite's model and compares: poses and odometry
to the last bit, stalls at the same steps, scans float32-equal (but for the races of Stage's
ranger thread it describes)."""
import os

import pytest
from stage_lite.model.world import load_world
from stage_lite.testing import golden

GOLDEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'golden')
CAPTURES = ('plan_drive', 'bodies_drive', 'formats', 'lesson_drive')
STEP_TOL = 1e-9      # m: poses are sums of 2 cm steps
# Real Stage 4.3.0 on the lesson's world: all four at 0.2 m/s, the front pair stalls at the
# hall's east wall after 1.74 m, at its 88th step, the back pair behind them after 3.36 m, at
# its 169th (the back robots' lasers, at 0.26 m, pass above the others)
LESSON_TRAVEL_M = [1.74, 3.36, 1.74, 3.36]
LESSON_STALL_STEP = [88, 169, 88, 169]


def capture(name, scratch_dir):
    """(arrays, meta, world file) of a golden capture."""
    gold, meta = golden.load(os.path.join(GOLDEN, 'data', name + '.npz'))
    return gold, meta, golden.world_path(gold, meta, os.path.join(GOLDEN, 'worlds'),
                                         str(scratch_dir))


@pytest.fixture(scope='module', params=CAPTURES)
def replayed(request, tmp_path_factory):
    gold, meta, world = capture(request.param, tmp_path_factory.mktemp(request.param))
    return gold, golden.replay(world, gold, meta)


@pytest.fixture(scope='module')
def lesson_world(tmp_path_factory):
    return capture('lesson_drive', tmp_path_factory.mktemp('lesson'))[2]


def test_every_step_of_the_capture_replayed(replayed):
    gold, frames = replayed
    assert len(frames) == len(gold['steps']) and gold['steps'][0] == 1


def test_poses_and_odometry_equal_real_stage(replayed):
    golden.check_poses(*replayed)


def test_stalls_at_the_same_steps_as_real_stage(replayed):
    golden.check_stalls(*replayed)


def test_scans_equal_real_stage_beam_by_beam(replayed):
    compared, _ = golden.check_scans(*replayed)
    assert compared > 0


def test_the_lessons_world_as_stage_reads_it(lesson_world):
    w = load_world(lesson_world)
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
                          % os.path.normpath(lesson_world)]
    occ, ox, oy, res = w.occupancy()
    assert res == 0.02 and occ.any()
    # the floor plan covers x in [-58.7, 0], y in [0, 54]
    assert ox == pytest.approx(-58.74, abs=0.03) and oy == pytest.approx(-0.04, abs=0.03)


def test_the_lessons_drive_front_pair_at_the_wall_back_pair_behind_them(lesson_world):
    w = load_world(lesson_world)
    for i in range(4):
        w.set_command(i, 0.2, 0.0, 0.0)
    stalled_at = [None] * 4
    for k in range(200):
        w.step()
        for i, r in enumerate(w.robots):
            if r.stalled and stalled_at[i] is None:
                stalled_at[i] = k + 1
    travel = [r.pose[0] - r.start_pose[0] for r in w.robots]
    assert travel == pytest.approx(LESSON_TRAVEL_M, abs=STEP_TOL)
    assert stalled_at == LESSON_STALL_STEP
    assert all(r.stalled for r in w.robots)
