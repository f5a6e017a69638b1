"""Stage's random numbers (glibc's streams) and event queues (libstdc++'s heap), exactly."""
import ctypes

import numpy as np
import pytest
from stage_lite.model.events import EventQueue
from stage_lite.model.glibc_random import RAND_MAX, Rand48, Random
from stage_lite.model.noise import RangerNoise
from stage_lite.model.scheduler import Scheduler

LIBC = ctypes.CDLL('libc.so.6')
LIBC.drand48.restype = ctypes.c_double


@pytest.mark.parametrize('seed', [1, 0, 7, 2 ** 31 + 5, 2 ** 32 - 1, 123456789])
def test_random_is_glibcs_stream_for_every_seed(seed):
    LIBC.srandom(ctypes.c_uint(seed))
    mine = Random(seed)
    assert [mine.random() for _ in range(1000)] == [LIBC.random() for _ in range(1000)]
    assert mine.block(500).tolist() == [LIBC.random() for _ in range(500)]
    assert mine.rand() == LIBC.rand()      # one stream: rand() is random()


def test_an_unseeded_random_is_srandom_1():
    assert [Random().random() for _ in range(1)] == [1804289383]
    r = Random()
    assert [r.random() for _ in range(3)] == [1804289383, 846930886, 1681692777]


@pytest.mark.parametrize('seed', [0, 1, 42, 2 ** 31 + 5, 2 ** 40 + 3])
def test_drand48_is_glibcs_stream(seed):
    LIBC.srand48(ctypes.c_long(seed))
    mine = Rand48(seed)
    assert all(mine.drand48() == LIBC.drand48() for _ in range(1000))


def test_an_unseeded_drand48_starts_from_glibcs_zero_state():
    assert Rand48().drand48() == 11 / 2 ** 48


# What std::priority_queue<Event> (libstdc++, g++ 12) gives for 17 models subscribed in
# order at t = 0, models 13, 15 updating every 200 and 300 us, the others every 100 us: the
# order each step takes them (a C++ program doing Stage's ConsumeQueue printed it).
LIBSTDCXX_ORDER = {
    100: [0, 2, 6, 14, 16, 5, 12, 11, 1, 4, 10, 9, 3, 8, 7],
    200: [0, 2, 5, 8, 7, 13, 6, 16, 14, 12, 1, 3, 11, 4, 9, 10],
    300: [0, 5, 6, 9, 10, 2, 8, 7, 16, 12, 4, 14, 1, 11, 15, 3],
    400: [0, 6, 2, 5, 3, 13, 10, 9, 8, 16, 11, 7, 12, 1, 4, 14],
    500: [0, 6, 4, 14, 2, 3, 5, 10, 8, 1, 9, 16, 12, 11, 7],
    600: [15, 0, 2, 11, 7, 13, 6, 14, 4, 3, 10, 12, 5, 8, 16, 1, 9],
    700: [0, 2, 6, 1, 9, 11, 7, 14, 3, 16, 4, 10, 8, 12, 5],
    800: [0, 2, 9, 12, 5, 13, 1, 6, 11, 14, 8, 7, 3, 10, 16, 4],
    900: [15, 2, 0, 16, 4, 9, 5, 12, 1, 11, 10, 6, 14, 3, 8, 7],
    1000: [13, 2, 9, 8, 7, 0, 4, 16, 5, 1, 3, 12, 11, 14, 10, 6],
    1100: [2, 0, 10, 6, 9, 7, 8, 4, 5, 14, 16, 1, 11, 3, 12],
    1200: [13, 2, 9, 3, 12, 15, 0, 6, 10, 7, 4, 11, 8, 5, 1, 14, 16],
}


def test_the_event_queue_takes_equal_times_in_libstdcxx_heap_order():
    intervals = [100] * 13 + [200, 100, 300, 100]
    queue = EventQueue()
    for model, interval in enumerate(intervals):
        queue.push(interval, model)
    for now, expected in LIBSTDCXX_ORDER.items():
        assert queue.consume(now, lambda m: intervals[m]) == expected, now


def test_an_item_not_queued_again_leaves_the_queue():
    queue = EventQueue()
    queue.push(100, 'a')
    queue.push(100, 'b')
    assert sorted(queue.consume(100, lambda m: None if m == 'a' else 100)) == ['a', 'b']
    assert queue.consume(200, lambda m: 100) == ['b']


class _Model:
    def __init__(self, kind, interval_us=100000):
        self.kind = kind
        self.interval_us = interval_us
        self.thread_safe = kind in ('ranger', 'fiducial', 'bumper')


def test_starting_a_thread_safe_model_draws_its_queue_from_random():
    stream = Random()
    expected = Random()
    scheduler = Scheduler(4, stream)
    ranger, position = _Model('ranger'), _Model('position')
    scheduler.subscribe(position, 0)
    scheduler.subscribe(ranger, 0)
    scheduler.subscribe(ranger, 0)                  # a second subscription starts nothing
    assert scheduler.queue_of[position] == 0
    assert scheduler.queue_of[ranger] == expected.random() % 4 + 1
    assert stream.state()[0].tolist() == expected.state()[0].tolist()


def test_callbacks_run_in_order_and_a_true_return_removes_one():
    scheduler = Scheduler(1, Random())
    model = _Model('position')
    calls = []
    scheduler.add_callback(model, 'update', lambda m, a: calls.append(a) or a == 'once', 'once')
    scheduler.add_callback(model, 'update', lambda m, a: calls.append(a), 'always')
    scheduler.call(model, 'update')
    scheduler.call(model, 'update')
    assert calls == ['once', 'always', 'always']
    with pytest.raises(ValueError, match='unknown callback kind'):
        scheduler.add_callback(model, 'tick', print)


def _stage_noise(stream, spare, ranges, rmax, prop, const):
    """Sensor::Update's draws, written straight from Stage's rules (one beam at a time)."""
    out = []
    for r in ranges:
        stream.random()                                 # the angle's simpleNoise
        if r < rmax:
            uniform = 2 * (stream.random() % 1000 * 0.001 - 0.5)
            if spare:
                g = np.sqrt(const * spare[0]) * np.sin(spare[1])
                spare.clear()
            else:
                r1 = max(stream.random() / RAND_MAX, 1e-100)
                r1 = -2 * np.log(r1)
                r2 = stream.random() / RAND_MAX * 2 * np.pi
                spare[:] = [r1, r2]
                g = np.sqrt(const * r1) * np.cos(r2)
            out.append(r + r * prop * uniform + g)
        else:
            out.append(r)
    return out


def test_ranger_noise_draws_as_stage_does_beam_by_beam():
    ranges = np.array([1.0, 5.0, 2.5, 0.3, 5.0, 4.99])
    noise = RangerNoise(Random(3))
    got = noise.apply(ranges, 5.0, (0.01, 0.05, 0.0))
    got2 = noise.apply(ranges, 5.0, (0.01, 0.05, 0.0))   # the spare carries over
    reference, spare = Random(3), []
    want = _stage_noise(reference, spare, ranges, 5.0, 0.05, 0.01)
    want2 = _stage_noise(reference, spare, ranges, 5.0, 0.05, 0.01)
    assert got.tolist() == pytest.approx(want, abs=0, rel=1e-15)
    assert got2.tolist() == pytest.approx(want2, abs=0, rel=1e-15)
    assert got[1] == 5.0 and got[4] == 5.0                  # a miss reads range max


@pytest.mark.parametrize('apply', ['apply', 'apply_rows', 'gaussian'])
def test_a_spare_drawn_without_noise_is_the_one_a_noisy_beam_then_takes(apply):
    # A sensor without noise (const 0, prop 0 or not) draws the gaussian's pair and keeps it
    # as drawn; the noisy beam after it (another sensor's, or the next update's) takes it, as
    # it takes Stage's spare: the same ranges to the last bit, the stream where Stage's is.
    quiet = np.array([1.0, 1.5])          # two hits: one draws the pair, one uses it up...
    first = np.array([0.7])               # ...so this one draws a pair and keeps its spare
    noisy = np.array([2.0, 0.4, 5.0, 1.1])
    noise = RangerNoise(Random(7))
    got = [noise.apply(quiet, 5.0, (0.0, 0.02, 0.0)), noise.apply(first, 5.0, (0.0, 0.0, 0.0))]
    if apply == 'apply':
        got.append(noise.apply(noisy, 5.0, (0.01, 0.05, 0.0)))
    elif apply == 'apply_rows':
        rows = noisy.copy()
        noise.apply_rows(rows, np.array([0, 4], np.int64), np.zeros(1, np.int64),
                         np.array([5.0]), np.array([0.05]), np.array([0.01]))
        got.append(rows)
    else:  # beam by beam (a sensor with angular noise): the angle's draw, then the range's
        got.append(np.array([(noise.angle_noise(), noise.range_noise(r, 5.0, (0.01, 0.05, 0.0)))[1]
                             for r in noisy]))
    reference, spare = Random(7), []
    want = [_stage_noise(reference, spare, quiet, 5.0, 0.02, 0.0),
            _stage_noise(reference, spare, first, 5.0, 0.0, 0.0),
            _stage_noise(reference, spare, noisy, 5.0, 0.05, 0.01)]
    for g, w in zip(got, want, strict=True):
        assert g.tolist() == pytest.approx(w, abs=0, rel=1e-15)
    assert got[2].tolist() != noisy.tolist()      # the noise is there
    assert noise.random.random() == reference.random()


def test_a_scan_without_noise_still_moves_the_stream_as_stages_does():
    stream = Random()
    out = RangerNoise(stream).apply(np.array([1.0, 8.0, 2.0]), 8.0, (0.0, 0.0, 0.0))
    assert out.tolist() == [1.0, 8.0, 2.0]
    reference = Random()
    _stage_noise(reference, [], [1.0, 8.0, 2.0], 8.0, 0.0, 0.0)
    assert stream.random() == reference.random()


def test_a_random_colour_takes_six_drand48_draws_and_keeps_the_last_three(tmp_path):
    # Model::Load draws Color(drand48(), drand48(), drand48()), then Color::Load reads the
    # same `color "random"` and draws r, g, b again; a position model first draws its
    # odometry error (4) in its constructor
    from stage_lite.model.world import load_world
    path = tmp_path / 'colours.world'
    path.write_text('position( name "p" pose [ 0 0 0 0 ] size [ 0.3 0.3 0.3 ] color "random" )\n'
                    'model( name "m" pose [ 2 0 0 0 ] size [ 0.3 0.3 0.3 ] color "random" )\n'
                    'model( name "red" pose [ 4 0 0 0 ] size [ 0.3 0.3 0.3 ] color "red" )\n')
    w = load_world(str(path), seed=7, stageros=False)
    ref = Rand48(7)
    d = [ref.drand48() for _ in range(4 + 6 + 6)]
    colours = {m.token: m.color for m in w.models}
    assert colours['p'] == (d[7], d[8], d[9], 1.0)
    assert colours['m'] == (d[13], d[14], d[15], 1.0)
    assert w.rand48.drand48() == ref.drand48()      # and the stream goes on from there
