"""The model of Stage's worker-thread race (race.py): its rule, the casts it makes stale, and
that a threaded world still repeats itself for a seed."""
import numpy as np
from stage_lite.model.race import MOVE_BEAMS_PER_BLOCK, WorkerRace, early_casts, move_starts
from stage_lite.model.world import load_world

ROOM = '''resolution 0.02
interval_sim 100
%s
model( pose [ 0 0 0 0 ] size [ 8 8 0.5 ] boundary 1 noblocks 1 )
'''
RING = 'ranger( %s )' % ' '.join(
    'sensor( pose [ 0 0 0 %d ] range [ 0 2 ] fov 30 samples 1 )' % (30 * k) for k in range(12))


def swarm(tmp_path, threads, n=16):
    body = ''.join('position( name "s%d" pose [ %.2f %.2f 0 %d ] size [ 0.1 0.1 0.1 ] %s'
                   ' ctrl "expand_swarm" )\n'
                   % (k, -3 + 0.6 * (k % 6), -3 + 0.6 * (k // 6), 47 * k % 360, RING)
                   for k in range(n))
    path = tmp_path / 'swarm.world'
    path.write_text(ROOM % threads + body)
    return str(path)


def test_the_main_thread_moves_the_robots_one_after_another():
    # robots 2, 0, 1 in that order; robot 0's move costs 5, robot 2's 1
    starts = move_starts(np.array([2, 0, 1]), np.array([5.0, 2.0, 1.0]))
    assert starts.tolist() == [1.0, 6.0, 0.0]


def test_a_ranger_is_stale_when_the_workers_reach_it_before_its_robots_move():
    # the workers take queue 2 then queue 1: ranger 2 starts at 0, ranger 0 at 4, ranger 1
    # at 7; robots 0, 1, 2 start moving at 5, 7, 0
    early = early_casts(np.array([2, 1]), np.array([1, 1, 2]), np.array([3.0, 3.0, 4.0]),
                        np.array([0, 1, 2]), np.array([5.0, 7.0, 0.0]))
    # 4 < 5: before; 7 = 7: the move has begun; 0 = 0: likewise
    assert early.tolist() == [True, False, False]
    # the other order: queue 1 first (rangers 0, 1 at 0 and 3), queue 2 at 6
    early = early_casts(np.array([1, 2]), np.array([1, 1, 2]), np.array([3.0, 3.0, 4.0]),
                        np.array([0, 1, 2]), np.array([5.0, 7.0, 0.0]))
    assert early.tolist() == [True, True, False]


def numpy_move_starts(move_order, move_cost):
    cost = move_cost[move_order]
    start = np.empty(len(move_cost), np.float64)
    start[move_order] = np.cumsum(cost) - cost
    return start


def numpy_early_casts(queue_order, queue, cost, robot, move_start):
    turn = np.zeros(int(max(queue_order.max(), queue.max(initial=0))) + 1, np.int64)
    turn[queue_order] = np.arange(len(queue_order))
    order = np.argsort(turn[queue], kind='stable')
    start = np.empty(len(queue), np.float64)
    start[order] = np.cumsum(cost[order]) - cost[order]
    return start < move_start[robot]


def test_the_clocks_equal_numpys_running_sums_to_the_bit():
    # the kernels against the model's first, numpy form: the same starts, bit for bit, and
    # the same casts, queues outside the order (taken with the first) included
    rng = np.random.default_rng(3)
    for _ in range(300):
        robots, rangers, threads = rng.integers(1, 40), rng.integers(0, 80), rng.integers(2, 8)
        move_order = rng.permutation(robots)
        move_cost = rng.choice([0.0, 2.0, 22.0, 0.1, 1e-17, 7.3], robots)
        starts = move_starts(move_order, move_cost)
        assert starts.tobytes() == numpy_move_starts(move_order, move_cost).tobytes()
        queue_order = rng.permutation(threads) + 1
        queue = rng.integers(0, threads + 2, rangers)
        cost = rng.choice([1.0, 12.0, 180.0, 0.3, 1e-16], rangers)
        robot = rng.integers(0, robots, rangers)
        assert (early_casts(queue_order, queue, cost, robot, starts).tolist()
                == numpy_early_casts(queue_order, queue, cost, robot, starts).tolist())


def test_a_still_robot_costs_the_main_thread_nothing():
    race = WorkerRace(2, 1, slot_beams=[1, 1], slot_robot=[0, 1], robot_blocks=[1, 1],
                      move_order=[0, 1])
    # robot 1's ranger starts at 0 or 1; robot 1 moves after robot 0's move (cost 2 x 1)
    assert race.stale(np.array([1, 2]), np.array([0, 1]), np.array([True, True]))[1]
    assert MOVE_BEAMS_PER_BLOCK > 1
    # robot 0 stands still: robot 1 moves at once, before any ranger
    assert not race.stale(np.array([1, 2]), np.array([0, 1]), np.array([False, True])).any()


def test_one_worker_thread_never_races_nor_a_world_loaded_without_the_race(tmp_path):
    for threads in ('', 'threads 0', 'threads 1'):
        assert load_world(swarm(tmp_path, threads, n=2), stageros=False).race is None
    assert load_world(swarm(tmp_path, 'threads 2', n=2), stageros=False).race is not None
    assert load_world(swarm(tmp_path, 'threads 2', n=2), stageros=False, race=False).race is None


def test_a_stale_cast_reads_the_robots_pose_before_the_move(tmp_path):
    path = tmp_path / 'one.world'
    path.write_text(ROOM % 'threads 3' + 'position( pose [ 1.5 0 0 0 ] size [ 0.3 0.3 0.3 ]'
                    ' ranger( sensor( range [ 0 5 ] fov 20 samples 5 ) ) )\n')
    for stale in (True, False):
        w = load_world(str(path), seed=2)
        w.set_command(0, 0.5, 0.0, 0.2)
        w.race.stale = lambda queue, slots, moving, s=stale: np.full(len(slots), s)
        w.step()
        w.step()
        view = w.robots[0].rangers[0]
        earlier = view.ranges.copy()
        before = w.robots[0].model.pose
        w.step()
        after = w.robots[0].model.pose
        assert after != before
        assert view.ranges.tobytes() == w.scan_from(view, before if stale else after).tobytes()
        assert view.ranges.tobytes() != earlier.tobytes()


def test_a_threaded_world_is_one_run_per_seed(tmp_path):
    path = swarm(tmp_path, 'threads 4')
    poses, stale = run_of(path)
    again, stale_again = run_of(path)
    assert poses.tobytes() == again.tobytes()
    assert all(a.tobytes() == b.tobytes() for a, b in zip(stale, stale_again, strict=True))
    early = np.concatenate(stale)
    assert 0 < early.sum() < early.size           # the race falls both ways
    other, stale_other = run_of(path, seed=5)
    assert other.tobytes() != poses.tobytes()
    assert any(a.tobytes() != b.tobytes() for a, b in zip(stale, stale_other, strict=False))


def test_a_run_number_draws_what_stage_takes_from_the_clock_and_keeps_random(tmp_path):
    path = swarm(tmp_path, 'threads 4')

    def loaded(**kw):
        w = load_world(path, stageros=False, **kw)
        return w, w.random.block(8).tolist(), w.rand48.drand48()

    plain, plain_random, plain_drand48 = loaded()
    first, first_random, first_drand48 = loaded(run=1)
    second, second_random, second_drand48 = loaded(run=2)
    # random() is an unseeded Stage's in every run (srandom(1)); drand48 is the clock's
    assert first_random == second_random == plain_random
    assert len({plain_drand48, first_drand48, second_drand48}) == 3
    assert (first.clock_seed, second.clock_seed, plain.clock_seed) == (1, 2, None)
    # the race is the run's: two runs differ, one run repeats itself
    poses, stale = run_of(path, run=1)
    again, stale_again = run_of(path, run=1)
    other, stale_other = run_of(path, run=2)
    assert poses.tobytes() == again.tobytes()
    assert all(a.tobytes() == b.tobytes() for a, b in zip(stale, stale_again, strict=True))
    assert any(a.tobytes() != b.tobytes() for a, b in zip(stale, stale_other, strict=False))
    # a seed moves random() itself, which no run of the real Stage does
    seeded = load_world(path, seed=2, stageros=False)
    assert seeded.random.block(8).tolist() != plain_random


def run_of(path, steps=40, **kw):
    """A threaded world's poses over `steps` steps and the race's stale casts of each
    (load_world's keywords: kw)."""
    w = load_world(path, stageros=False, **kw)
    stale = []
    draw = w.race.stale
    w.race.stale = lambda *a: stale.append(draw(*a)) or stale[-1]
    poses = []
    for _ in range(steps):
        w.step()
        poses.append(w.state.pose.copy())
    return np.array(poses), stale
