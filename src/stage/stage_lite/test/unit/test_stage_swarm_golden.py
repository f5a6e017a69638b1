"""100 of Stage's benchmark swarmbots (expand_swarm, 4 worker threads) on the workspace's own
open floor (stage_lite.swarm_world), held to ten runs of the real Stage 4.3.0
(test/golden/swarm/: its README says how they were captured): the same poses, to the bit,
for as long as the real runs agree with each other, and the swarm's statistics within the
real runs' range afterwards, where the runs part (Stage's worker threads race its moves)."""
import hashlib
import json
import os

import numpy as np
import pytest
from stage_lite import swarm_world
from stage_lite.model.world import load_world
from stage_lite.testing import swarm_stats

GOLDEN = os.path.join(os.path.dirname(__file__), '..', 'golden', 'swarm', 'swarm_100.npz')
ROBOTS = 100


@pytest.fixture(scope='module')
def golden():
    data = np.load(GOLDEN)
    return json.loads(str(data['meta'])), data


@pytest.fixture(scope='module')
def run(golden, tmp_path_factory):
    """stage_lite's poses (states, robots, 3) over the real runs' states, from state 0."""
    meta, _ = golden
    text = swarm_world.world_text(ROBOTS)
    assert hashlib.sha256(text.encode()).hexdigest() == meta['world_sha256'], \
        'swarm_world.world_text changed since the golden runs: capture them again (README)'
    path = tmp_path_factory.mktemp('swarm') / 'swarm_100.world'
    path.write_text(text)
    w = load_world(str(path), stageros=False, model_order=meta['model_order'])
    poses = [[r.pose for r in w.robots]]
    for _ in range(meta['states'] - 1):
        w.step()
        poses.append([r.pose for r in w.robots])
    return np.array(poses)


def test_poses_equal_the_real_stages_to_the_bit_while_its_runs_agree(golden, run):
    meta, data = golden
    agreed = data['agreed']
    assert meta['runs'] == 10 and meta['agree_through_state'] == 2   # the data say so
    # state 2: the first moves, headings from 12 sensors at 0 to 330 degrees (Pose::Load
    # keeps 210 .. 330 degrees as written; normalised, 35 robots were off in the last bit)
    assert run[:len(agreed)].tobytes() == agreed.tobytes()


def test_the_swarm_fits_the_real_runs_spread_as_a_real_run_does(golden, run):
    # per statistic, at as many of the 31 one-second times as the real run that fits the
    # others' min..max least (path 11, moving share 20, speed 21; stage_lite gives 30, 21
    # and 24, without the race model 15, 18 and 21)
    meta, data = golden
    times = data['stat_t_s'].astype(float)
    t_s = np.arange(run.shape[0]) * meta['interval_sim_us'] / 1e6
    ours = swarm_stats.swarm_stats(t_s, run, times)
    for name in ('path_m', 'moving_share', 'speed_mps'):
        real = data['stat_' + name]
        inside = swarm_stats.within_runs(ours[name], real)
        least = swarm_stats.runs_within_the_others(real).min()
        assert inside.sum() >= least, (name, int(inside.sum()), int(least), ours[name].round(3))
