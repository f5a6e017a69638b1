"""stage_lite.testing.swarm_stats and stage_capture_file: swarm statistics of runs and the
reader of real Stage's captures, on hand-made runs whose answers are known."""
import json
import math
import struct

import numpy as np
import pytest
from stage_lite.testing import stage_capture_file, swarm_stats

TOL = 1e-12   # the statistics are sums of a few exact steps


def straight_run(n_steps=21, dt=0.1, speeds=(1.0, 0.0), headings=(0.0, 0.0)):
    """Robots driving straight at constant speeds (m/s) from x = 0, y = 10 * index."""
    t = np.arange(n_steps) * dt
    pose = np.zeros((n_steps, len(speeds), 3))
    for k, (v, a) in enumerate(zip(speeds, headings, strict=True)):
        pose[:, k, 0] = v * t * math.cos(a)
        pose[:, k, 1] = 10.0 * k + v * t * math.sin(a)
        pose[:, k, 2] = a
    return t, pose


def test_path_length_sums_steps():
    pose = np.zeros((3, 1, 3))
    pose[1, 0, :2] = (3.0, 4.0)
    pose[2, 0, :2] = (3.0, 0.0)
    assert swarm_stats.path_length(pose)[:, 0].tolist() == [0.0, 5.0, 9.0]


def test_straight_run_statistics():
    t, pose = straight_run()
    out = swarm_stats.swarm_stats(t, pose, [1.0, 2.0])
    assert out['t_s'] == pytest.approx([1.0, 2.0], abs=TOL)
    assert out['path_m'] == pytest.approx([0.5, 1.0], abs=TOL)   # one robot of two moves
    assert out['moving_share'].tolist() == [0.5, 0.5]
    assert out['speed_mps'] == pytest.approx([0.5, 0.5], abs=TOL)


def test_first_window_counts_from_the_start():
    t, pose = straight_run(speeds=(1.0, 1.0))
    out = swarm_stats.swarm_stats(t, pose, [0.5])
    assert out['speed_mps'] == pytest.approx([0.5], abs=TOL)   # 0.5 m in a 1 s window


@pytest.mark.parametrize('headings, expected', [
    ((0.0, 0.0), 1.0),
    ((0.0, math.pi), 0.0),
    ((0.0, math.pi / 2), math.sqrt(0.5)),
])
def test_alignment(headings, expected):
    assert swarm_stats.alignment(np.array(headings)) == pytest.approx(expected, abs=TOL)


def test_flocking_and_places():
    t, pose = straight_run(speeds=(1.0, 1.0), headings=(0.0, math.pi / 2))
    out = swarm_stats.swarm_stats(t, pose, [0.0], flocking=True,
                                  places={'sink': [[0.0, 0.0], [0.0, 20.0]]})
    assert out['alignment'] == pytest.approx([math.sqrt(0.5)], abs=TOL)
    assert out['spacing_m'] == pytest.approx([10.0], abs=TOL)
    assert out['dist_sink_m'] == pytest.approx([5.0], abs=TOL)


def test_nearest_neighbour_three_points():
    xy = np.array([[0.0, 0.0], [1.0, 0.0], [5.0, 0.0]])
    assert swarm_stats.nearest_neighbour(xy) == pytest.approx((1 + 1 + 4) / 3, abs=TOL)


def test_parting_step():
    t, a = straight_run()
    b = a.copy()
    b[7:, 0, 0] += 0.005
    b[12:, 0, 0] += 0.02
    assert swarm_stats.parting_step([a, a.copy()]) is None
    assert swarm_stats.parting_step([a, b]) == 12
    assert swarm_stats.parting_step([a, b], tol_m=1e-9) == 7
    assert swarm_stats.parting_step([a, a, b[:10]], tol_m=1e-9) == 7


@pytest.mark.parametrize('call, match', [
    (lambda: swarm_stats.swarm_stats([0.0, 0.1], np.zeros((2, 1, 2)), [0.0]), 'pose'),
    (lambda: swarm_stats.swarm_stats([0.0, 0.1, 0.2], np.zeros((2, 1, 3)), [0.0]), 't_s'),
    (lambda: swarm_stats.swarm_stats([0.1, 0.0], np.zeros((2, 1, 3)), [0.0]), 'increase'),
    (lambda: swarm_stats.swarm_stats([0.0, 0.1], np.zeros((2, 1, 3)), [5.0]), 'no state'),
    (lambda: swarm_stats.swarm_stats([0.0, 0.1], np.full((2, 1, 3), np.nan), [0.0]), 'finite'),
    (lambda: swarm_stats.swarm_stats([0.0, 0.1], np.zeros((2, 1, 3)), [0.0], window_s=0),
     'window_s'),
    (lambda: swarm_stats.nearest_neighbour(np.zeros((1, 2))), 'xy'),
    (lambda: swarm_stats.nearest_place(np.zeros((1, 2)), np.zeros((0, 2))), 'places'),
    (lambda: swarm_stats.parting_step([np.zeros((2, 1, 3))]), 'two runs'),
])
def test_bad_input_raises(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def capture_bytes(header, records):
    text = json.dumps(header).encode()
    return stage_capture_file.MAGIC + struct.pack('<I', len(text)) + text + records


def test_reader_parses_records_and_drops_a_cut_record():
    header = {'position_models': ['r0', 'r1'], 'flag_models': ['sink'], 'interval_sim_us': 100000}
    dtype = stage_capture_file.record_dtype(2, 1)
    rec = np.zeros(3, dtype=dtype)
    rec['t_us'] = [0, 100000, 200000]
    rec['pose'][1, 1] = (1.5, -2.0, 0.25)
    rec['stall'][2, 0] = 1
    rec['flags'][2, 0] = 7
    data = capture_bytes(header, rec.tobytes() + b'\0' * 5)
    got_header, arrays = stage_capture_file.parse(data)
    assert got_header == header
    assert arrays['t_s'].tolist() == [0.0, 0.1, 0.2]
    assert arrays['pose'].shape == (3, 2, 3)
    assert arrays['pose'][1, 1].tolist() == [1.5, -2.0, 0.25]
    assert arrays['stall'].tolist() == [[False, False], [False, False], [True, False]]
    assert arrays['flags'][:, 0].tolist() == [0, 0, 7]


@pytest.mark.parametrize('data', [b'NOTACAPT' + b'\0' * 8,
                                  stage_capture_file.MAGIC + b'\xff\0\0\0{}'])
def test_reader_rejects_bad_files(data):
    with pytest.raises(ValueError):
        stage_capture_file.parse(data)


def test_within_runs_takes_the_runs_min_to_max_at_each_time():
    runs = np.array([[0.0, 1.0, 2.0], [1.0, 1.0, 4.0]], np.float32)
    values = np.array([0.5, 1.0 + 5e-7, 4.1])
    assert swarm_stats.within_runs(values, runs).tolist() == [True, True, False]
    with pytest.raises(ValueError):
        swarm_stats.within_runs(values[:2], runs)


def test_each_run_is_held_to_the_other_runs_range():
    runs = np.array([[0.0, 1.0, 2.0, 3.0],
                     [0.0, 2.0, 3.0, 4.0],
                     [0.0, 1.5, 2.5, 9.0]])
    # run 0 is below the others at times 1-3; run 1 above at 1-2, inside at 3 (3..9);
    # run 2 inside at 1-2, above at 3
    assert swarm_stats.runs_within_the_others(runs).tolist() == [1, 2, 3]
    with pytest.raises(ValueError):
        swarm_stats.runs_within_the_others(runs[:1])
