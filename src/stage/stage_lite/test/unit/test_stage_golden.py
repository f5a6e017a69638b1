"""stage_lite held to real Stage 4.3.0 + stage_ros 1.8.0, step by step and beam by beam.

The golden data (../golden/data/*.npz) are captures of real Stage, built from source, on the
workspace's own worlds (../golden/worlds/: a turned floor plan with thin, diagonal and grey
walls at negative coordinates; bodies of every kind with robots of every drive; one floor
plan per image format), made as ../golden/README.md says. stage_lite.testing.golden replays
each in stage_lite's model and compares: poses and odometry to the last bit, stalls at the
same steps, scans float32-equal (but for the races of Stage's ranger thread it describes)."""
import os

import pytest
from stage_lite.testing import golden

GOLDEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'golden')
CAPTURES = ('plan_drive', 'bodies_drive', 'formats')


@pytest.fixture(scope='module', params=CAPTURES)
def replayed(request):
    gold, meta = golden.load(os.path.join(GOLDEN, 'data', request.param + '.npz'))
    frames = golden.replay(os.path.join(GOLDEN, 'worlds', meta['world']), gold, meta)
    return gold, frames


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
