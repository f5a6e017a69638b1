"""Stage's random numbers, noise and controllers held to the real Stage 4.3.0, bit for bit.

golden/data/draws.npz: four runs of the real `stage -g` on golden/worlds/draws.world (two
wanderers, a laser under Stage's lasernoise controller, a ranger with Stage's own noise,
constant, proportional and angular, and `alwayson`), 30 s each, recorded by a probe plugin
(golden/probe/stage_probe.cc): each step's scans (hits and the sum of the ranges), poses and
glibc random()'s state. The real runs part now and then on a scan and the random() state:
their rangers race the moves in a worker thread (a ranger casting before its robot has
moved reads from its old pose, and its noise draws as many numbers as that scan's hits
ask), and a shifted random() later makes an avoidance last another length. stage_lite,
which casts after the moves, must give every pose of every run up to the step where they
part, a whole run the real Stage made, and at every step a scan and a random() state that a
real run gave.
"""
import os

import numpy as np
import pytest
from stage_lite.model.world import load_world

GOLDEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'golden')
DATA = np.load(os.path.join(GOLDEN, 'data', 'draws.npz'))
WORLD = os.path.join(GOLDEN, 'worlds', 'draws.world')


@pytest.fixture(scope='module')
def run():
    """Our run of the world, as the real data holds it: per step the poses, stalls, scans
    (hits, sequential sum) and random()'s state words."""
    w = load_world(WORLD, stageros=False)
    robots = {r.model.token: r for r in w.robots}
    rangers = {g.token: g for r in w.robots for g in r.ranger_models}
    out = {'pose': [], 'stall': [], 'hits': [], 'sum': [], 'rng': [], 't_us': []}
    for _ in DATA['t_us']:
        w.step()
        out['t_us'].append(w.sim_time_us)
        out['pose'].append([robots[t].pose for t in DATA['robots']])
        out['stall'].append([robots[t].stalled for t in DATA['robots']])
        hits, sums = [], []
        for token in DATA['rangers']:
            s = rangers[token].sensors[0]
            total = 0.0
            for r in s.ranges.tolist():      # in beam order, as the probe adds them
                total += r
            hits.append(int((s.ranges < s.range[1]).sum()))
            sums.append(total)
        out['hits'].append(hits)
        out['sum'].append(sums)
        out['rng'].append(w.random.table.tolist())
    return {k: np.array(v) for k, v in out.items()}


def parting_step():
    """The first step at which two real runs' poses differ."""
    apart = (DATA['pose'] != DATA['pose'][0]).any(axis=(0, 2, 3))
    return int(np.argmax(apart)) if apart.any() else len(apart)


def test_the_real_runs_part_on_races():
    # the robots drive, turn and (the lasernoise and noisy ones) stand
    path = np.abs(np.diff(DATA['pose'][0, :, :, :2], axis=0)).sum(axis=(0, 2))
    assert dict(zip(DATA['robots'], path > 1.0, strict=True)) == {
        'jitter': False, 'noisy': False, 'roamer': True, 'wanderer': True}
    # a race shifts random() for good: later avoidances last other lengths, and the runs
    # part (at 9.2 s when captured); before that, the runs agree on every pose
    assert 50 < parting_step() < len(DATA['t_us'])


def test_every_pose_is_the_real_stages(run):
    assert run['t_us'].tolist() == DATA['t_us'].tolist()
    part = parting_step()
    assert (run['pose'][:part] == DATA['pose'][:, :part]).all()   # to the last bit
    assert (run['stall'][:part] == DATA['stall'][:, :part]).all()
    # and the whole 30 s are a run the real Stage made
    assert any(np.array_equal(run['pose'], p) and np.array_equal(run['stall'], s)
               for p, s in zip(DATA['pose'], DATA['stall'], strict=True))


def test_every_scan_and_random_state_is_one_a_real_run_gave(run):
    steps = range(len(DATA['t_us']))
    scans = [(run['hits'][k] == DATA['scan_hits'][:, k]).all(axis=1)
             & (run['sum'][k] == DATA['scan_sum'][:, k]).all(axis=1) for k in steps]
    assert all(s.any() for s in scans), [k for k, s in enumerate(scans) if not s.any()]
    states = [(run['rng'][k] == DATA['rng'][:, k]).all(axis=1) for k in steps]
    assert all(s.any() for s in states), [k for k, s in enumerate(states) if not s.any()]
