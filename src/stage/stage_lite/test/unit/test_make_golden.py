"""test/golden/stage_worlds/make_golden.py's --add: a later capture's runs joined to a world's
golden data (the arrays' runs one after another, the parting steps found again)."""
import importlib.util
import json
import os

import numpy as np
import pytest

SCRIPT = os.path.join(os.path.dirname(__file__), '..', 'golden', 'stage_worlds',
                      'make_golden.py')


@pytest.fixture(scope='module')
def make_golden():
    spec = importlib.util.spec_from_file_location('make_golden', SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def golden(prefix, seeds, states=5, kept=(), world='w'):
    """A world's arrays as make() writes them: prefix (runs, steps + 1, robots, 3); kept:
    the flag models that held a flag (of source, sink and r0 .. r2), each holding its
    column's number plus one at every state."""
    runs, steps, robots = prefix.shape[0], prefix.shape[1] - 1, prefix.shape[2]
    models = ['r%d' % i for i in range(robots)]
    meta = dict(world_name=world, states=states, prefix_steps=steps, pose_every=1,
                position_models=models, flag_models=['source', 'sink'] + models,
                kept_flag_models=list(kept), interval_sim_us=100000,
                runs=['run%d.stgcap' % (k + 1) for k in range(runs)], seeds=seeds,
                parting_state={'1cm': None, '1e-9': None})
    flags = np.zeros((runs, states, len(kept)), np.uint16) + np.arange(1, len(kept) + 1)
    return dict(meta=np.array(json.dumps(meta)), prefix_pose=prefix,
                pose=np.zeros((runs, states, robots, 3), np.float32),
                stall=np.zeros((runs, states, 1), np.uint8),
                flags=flags.astype(np.uint16),
                stat_t_s=np.array([0.0, 1.0], np.float32),
                stat_path_m=np.arange(2 * runs, dtype=np.float32).reshape(runs, 2) + seeds[0])


def test_added_runs_follow_the_first_ones_and_the_parting_is_found_again(make_golden):
    same = np.zeros((2, 4, 3, 3))                       # two runs that never part
    later = np.zeros((1, 4, 3, 3))
    later[0, 2:, 1, 0] = 0.02                           # robot 1 2 cm away from state 2 on
    out = make_golden.added_runs(golden(same, [10, 11]), golden(later, [20]))
    meta = json.loads(str(out['meta']))
    assert meta['runs'] == ['run1.stgcap', 'run2.stgcap', 'added/run1.stgcap']
    assert meta['seeds'] == [10, 11, 20] and meta['batches'] == [2, 1]
    assert meta['parting_state'] == {'1cm': 2, '1e-9': 2}
    assert out['prefix_pose'].shape == (3, 4, 3, 3) and out['pose'].shape[0] == 3
    assert out['stat_path_m'][:, 0].tolist() == [10, 12, 20]   # the old runs' rows first
    assert out['stat_t_s'].tolist() == [0.0, 1.0]
    again = make_golden.added_runs(out, golden(same[:1], [30]))  # a third batch
    assert json.loads(str(again['meta']))['batches'] == [2, 1, 1]


def test_flag_counts_keep_every_model_that_held_one_in_either_capture(make_golden):
    runs = np.zeros((1, 4, 3, 3))
    out = make_golden.added_runs(golden(runs, [1], kept=['sink', 'r2']),
                                 golden(runs, [2], kept=['source', 'sink']))
    assert json.loads(str(out['meta']))['kept_flag_models'] == ['source', 'sink', 'r2']
    assert out['flags'][:, 0].tolist() == [[0, 1, 2], [1, 2, 0]]    # 0 where none was held


@pytest.mark.parametrize('change, match', [
    (dict(states=6), 'states differs'),
    (dict(world='other'), 'world_name differs'),
])
def test_added_runs_of_another_capture_are_refused(make_golden, change, match):
    runs = np.zeros((1, 4, 3, 3))
    with pytest.raises(SystemExit, match=match):
        make_golden.added_runs(golden(runs, [1]), golden(runs, [2], **change))


def test_runs_of_another_model_order_are_named(make_golden, capsys):
    order = ['cave', 'r0', 'r1']
    headers = [dict(model_order=order), dict(model_order=order),
               dict(model_order=['r0', 'cave', 'r1']), dict()]
    assert make_golden.same_model_order('w', ['run1', 'run2', 'run3', 'run4'], headers) is False
    assert "w: the model order of run3 differs from run1's" in capsys.readouterr().err
    # a capture made before stage_capture wrote the order says nothing either way
    assert make_golden.same_model_order('w', ['run1', 'run4'], [headers[0], headers[3]])
    assert capsys.readouterr().err == ''
