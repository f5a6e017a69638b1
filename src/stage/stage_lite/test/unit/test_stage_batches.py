"""The step's kernels and batches do what the world's one-by-one code does, to the last bit:
every robot's update and move (motion.py) against World._step_each (power packs too), the
fiducial finders' kernel against Fiducial.update_one_by_one, and the controllers' batches
(expand_swarm, pioneer_flocking, fasr2, fasr) against their callbacks called one by one."""
import os

import numpy as np
import pytest
from stage_lite.controllers import _fasr2_batch as fasr2_batch
from stage_lite.controllers import _fasr_batch as fasr_batch
from stage_lite.controllers import fasr, fasr2
from stage_lite.model import fiducial as fiducial_module
from stage_lite.model import sensing
from stage_lite.model import world as world_module
from stage_lite.model.jit import numba_threads
from stage_lite.model.world import load_world

STEPS = 60

ROOM = '''resolution 0.02
interval_sim 100
model( pose [ 0 0 0 0 ] size [ 6 6 0.5 ] boundary 1 noblocks 1 )
model( pose [ 1.2 0.4 0 30 ] size [ 0.5 0.3 0.5 ] )
'''
RING = 'ranger( %s )' % ' '.join(
    'sensor( pose [ 0 0 0 %d ] range [ 0 2 ] fov 30 samples 1 )' % (30 * k) for k in range(12))
SONARS = 'ranger( %s )' % ' '.join(
    'sensor( pose [ 0.1 0 0 %d ] range [ 0 5 ] fov 15 samples 1 )' % a
    for a in (90, 50, 30, 10, -10, -30, -50, -90))


def place(k, columns=5, spacing=0.9):
    return '%.2f %.2f 0 %d' % (-2.2 + spacing * (k % columns), -2.2 + spacing * (k // columns),
                               (37 * k) % 360 - 180)


def write(tmp_path, body):
    path = tmp_path / 'w.world'
    path.write_text(ROOM + body)
    return str(path)


def snapshot(w):
    s = w.state
    return [a.copy() for a in (s.pose, s.goal, s.mode, s.velocity, s.est, s.stalled,
                               s.twist, w._beam_ranges, w._beam_intensities,
                               w.rand48.state, *w.random.state())]


def assert_same(a, b, step):
    for x, y in zip(a, b, strict=True):
        assert x.tobytes() == y.tobytes(), step


DRIVES = '''
position( name "d" pose [ %s ] size [ 0.4 0.4 0.3 ] laser( )
          model( pose [ 0.1 0 0 0 ] size [ 0.1 0.1 0.1 ] ) )
position( name "o" pose [ %s ] size [ 0.3 0.3 0.3 ] drive "omni" localization "odom"
          odom_error [ 0.02 0.03 0 0.04 ] laser( ) )
position( name "c" pose [ %s ] size [ 0.5 0.3 0.3 ] drive "car" wheelbase 0.4 laser( ) )
position( name "a" pose [ %s ] size [ 0.3 0.3 0.3 ] laser( ) )
position( name "g" pose [ %s ] size [ 0.3 0.3 0.3 ] localization "odom" laser( ) )
position( name "s" pose [ %s ] size [ 0.3 0.3 0.3 ] )
''' % tuple(place(k) for k in range(6))
LASER = 'define laser ranger ( sensor( range [ 0 4 ] fov 180 samples 31 noise [ 0.01 0.02 0 ] ) )\n'


def drive(w):
    """Commands of every kind: velocity (diff, omni, car), acceleration, GoTo; one robot
    driven into the box and the wall."""
    w.set_command(0, 0.6, 0.0, 0.3)
    w.set_command(1, 0.3, -0.4, 0.2)
    w.set_command(2, 0.5, 0.0, 0.4)
    w.handle(w.robots[3].model).set_acceleration(0.4, 0.0, -0.3)
    w.handle(w.robots[4].model).go_to(1.5, -1.0, 0.5)
    w.set_command(5, 1.0, 0.0, 0.0)


@pytest.mark.parametrize('threads', ['', 'threads 3\n'])   # with Stage's race (race.py)
def test_the_kernels_move_every_robot_as_the_world_does_one_by_one(tmp_path, threads):
    path = write(tmp_path, threads + LASER + DRIVES)
    fast, each = load_world(path, seed=3), load_world(path, seed=3)
    each.motion = None                  # World._step_each: robot by robot, Python
    assert fast.motion is not None
    stale = []
    if threads:
        draw = fast.race.stale
        fast.race.stale = lambda *a: stale.append(draw(*a)) or stale[-1]
    drive(fast)
    drive(each)
    stalls = 0
    for step in range(STEPS):
        fast.step()
        each.step()
        assert_same(snapshot(fast), snapshot(each), step)
        stalls += int(fast.state.stalled.sum())
        for v, u in zip(fast.robots, each.robots, strict=True):
            for a, b in zip(v.rangers, u.rangers, strict=True):
                assert a.ranges.tobytes() == b.ranges.tobytes(), step
    assert stalls > 0                    # the test drove into something
    if threads:                          # some casts were stale, some not
        assert 0 < np.concatenate(stale).sum() < np.concatenate(stale).size


def test_the_kernels_draw_and_charge_power_packs_as_the_world_does_one_by_one():
    # fasr2's foragers: packs drawn by speed and sensors, one docking and charging
    path = os.path.join(os.path.dirname(__file__), '..', 'worlds', 'fasr2_small.world')
    fast, each = load_world(path, seed=5), load_world(path, seed=5)
    each.motion = None
    assert fast.motion is not None
    packs = [[r.model.power_pack for r in w.robots] for w in (fast, each)]
    charged = 0
    for step in range(300):
        fast.step()
        each.step()
        assert_same(snapshot(fast), snapshot(each), step)
        assert [(p.stored, p.charging) for p in packs[0]] == \
            [(p.stored, p.charging) for p in packs[1]], step
        charged += sum(p.charging for p in packs[0])
    assert charged > 0 and packs[0][0].stored < packs[0][0].capacity    # both happened


def flocking_world(tmp_path, n=12, columns=4, spacing=1.1):
    body = ''.join('position( name "p%d" pose [ %s ] size [ 0.35 0.3 0.25 ] fiducial_return 1'
                   ' %s fiducial( range_max 4 ) ctrl "pioneer_flocking" )\n'
                   % (k, place(k, columns, spacing), SONARS) for k in range(n))
    return write(tmp_path, body)


def swarm_world(tmp_path, n=20):
    body = ''.join('position( name "s%d" pose [ %s ] size [ 0.1 0.1 0.1 ] %s'
                   ' ctrl "expand_swarm" )\n' % (k, place(k, 5, 0.5), RING) for k in range(n))
    return write(tmp_path, body)


def fasr2_world(_):
    """fasr2's three robots on the workspace's small cave: one walks, one carries, one is
    hungry (it docks, charges and undocks within the run)."""
    return os.path.join(os.path.dirname(__file__), '..', 'worlds', 'fasr2_small.world')


def controller_state(w):
    """What fasr2's robots keep in Python (the batch reads and writes some of it)."""
    robots = [cb.function.__self__ for (m, kind), entries in w.scheduler.callbacks.items()
              for cb, _, _ in entries if isinstance(getattr(cb.function, '__self__', None),
                                                     fasr2.Robot)]
    return [(r.pos.token, r.mode, r.avoid_count, r.wait_started_at, r.goal.token,
             None if r.plan is None else r.plan.id, r.force_recharge, r.charger_ahoy,
             dict(r.subscribed), r.cached_goal_pose) for r in robots]


@pytest.mark.parametrize('make, steps', [(swarm_world, STEPS), (flocking_world, STEPS),
                                         (fasr2_world, 1500)])
def test_the_batches_are_the_callbacks_one_by_one(tmp_path, make, steps):
    path = make(tmp_path)
    batched = load_world(path, seed=7, stageros=False)
    alone = load_world(path, seed=7, stageros=False)
    alone.batches = False
    for step in range(steps):
        batched.step()
        alone.step()
        assert_same(snapshot(batched), snapshot(alone), step)
        assert controller_state(batched) == controller_state(alone), step
    assert batched._plans and not alone._plans            # the batch did run
    assert np.abs(batched.state.velocity).sum() > 0


def test_fasr2s_kernel_does_most_updates_and_leaves_the_rest_to_python(monkeypatch):
    # over the small cave's run each robot is, at times, the kernel's case and not (avoiding
    # with a draw, hungry, docking): both paths must be taken, the kernel's most often
    calls = {'kernel': 0, 'python': 0}
    run = fasr2_batch.Fasr2Batch.run

    def counted_run(self, plan, rows):
        done = run(self, plan, rows)
        calls['kernel'] += done
        calls['python'] += int(done < rows.size)
        return done
    monkeypatch.setattr(fasr2_batch.Fasr2Batch, 'run', counted_run)
    w = load_world(fasr2_world(None), seed=7, stageros=False)
    for _ in range(1500):
        w.step()
    assert calls['kernel'] > 2 * calls['python'] > 0


def foragers_state(w):
    """What fasr's robots keep in Python (the batch reads and writes some of it)."""
    robots = [cb.function.__self__ for (m, kind), entries in w.scheduler.callbacks.items()
              for cb, _, _ in entries if isinstance(getattr(cb.function, '__self__', None),
                                                     fasr.Forager)]
    return [(r.pos.token, r.mode, r.avoid_count, r.charger_ahoy, r.charger_range,
             r.work_get, r.work_put, r.at_dest, r.pos.get_flag_count()) for r in robots]


def test_fasrs_batches_are_its_updates_one_by_one(monkeypatch):
    # fasr's three robots on the small room (one docks, charges and undocks, one fetches a
    # flag, one delivers it): each batch's case most often, Python's too (a laser's update
    # while hungry or docking, a finder's that saw the charger, a position's at the source
    # or the sink), and avoids drawn
    calls = {(batch, path): 0 for batch in ('lasers', 'positions')
             for path in ('batch', 'python')}

    def counted(name, run):
        def counted_run(self, plan, rows):
            done = run(self, plan, rows)
            calls[name, 'batch'] += done
            calls[name, 'python'] += int(done < rows.size)
            return done
        return counted_run
    monkeypatch.setattr(fasr_batch.FasrBatch, 'run',
                        counted('lasers', fasr_batch.FasrBatch.run))
    monkeypatch.setattr(fasr_batch.FasrPositionBatch, 'run',
                        counted('positions', fasr_batch.FasrPositionBatch.run))
    path = os.path.join(os.path.dirname(__file__), '..', 'worlds', 'fasr_small.world')
    batched = load_world(path, seed=7, stageros=False)
    alone = load_world(path, seed=7, stageros=False)
    alone.batches = False
    avoided = set()
    for step in range(600):
        batched.step()
        alone.step()
        assert_same(snapshot(batched), snapshot(alone), step)
        state = foragers_state(batched)
        assert state == foragers_state(alone), step
        avoided.update(token for token, _, count, *_ in state if count > 0)
    for name in ('lasers', 'positions'):
        assert calls[name, 'batch'] > 2 * calls[name, 'python'] > 0, name
    assert avoided


@pytest.mark.parametrize('robots', [12, 34])     # 34 * 34 pairs: the threads' kernel
def test_the_finders_kernel_is_their_rule_one_by_one(tmp_path, monkeypatch, robots):
    assert (robots * robots >= sensing.PARALLEL_CANDIDATES) == (robots == 34)
    path = flocking_world(tmp_path, robots, 7, 0.7)
    fast, each = load_world(path, seed=5, stageros=False), load_world(path, seed=5,
                                                                       stageros=False)

    class OneByOne:
        """prepare_ids's Finding, the finders updated one by one when it is published."""
        args = None

        def __init__(self, ids, models, index, sight, layer):
            self.update = [(models(i), index, sight, layer) for i in ids.tolist()]

        def run(self):
            pass

        def publish(self):
            for finder, *how in self.update:
                finder.update_one_by_one(*how)

    seen = 0
    for step in range(STEPS):
        fast.step()
        with monkeypatch.context() as m:
            m.setattr(world_module, 'prepare_finders', OneByOne)
            each.step()
        assert_same(snapshot(fast), snapshot(each), step)
        for f, g in zip(fast.models, each.models, strict=True):
            if isinstance(f, fiducial_module.Fiducial):
                assert f.nearest() == g.nearest()
                assert f.fiducials == [r.__class__(**{**r.__dict__, 'model': fast.models[
                    r.model.index]}) for r in g.fiducials], step
                seen += len(f.fiducials)
    assert seen > 0


@pytest.mark.parametrize('robots', [12, 34])
def test_a_finder_read_for_its_nearest_only_finds_the_same_nearest(tmp_path, robots):
    """pioneer_flocking reads its finders' nearest only, so their updates find it alone
    (finders._see_nearest: the rays to the others skipped). Against the same world whose
    finders make all their readings: the same run, bit for bit, the same nearest at every
    step, and the readings, asked for in the step, made as the full update makes them; a
    step later they cannot be made, and saying so is an error."""
    path = flocking_world(tmp_path, robots, 7, 0.7)
    near, full = load_world(path, seed=5, stageros=False), load_world(path, seed=5,
                                                                       stageros=False)
    full.fiducial_index.nearest_only_allowed = False
    finders = [m for m in near.models if isinstance(m, fiducial_module.Fiducial)]
    assert len(finders) == robots and all(f.nearest_only for f in finders)
    skipped = seen = 0
    for step in range(STEPS):
        near.step()
        full.step()
        assert_same(snapshot(near), snapshot(full), step)
        skipped += sum(f._seen is not None and f._seen[0].count[f._seen[1]] < 0
                       for f in finders)
        for f in finders:
            g = full.models[f.index]
            assert f.nearest() == g.nearest(), step
            if step % 3 == 0:
                assert f.seen_count() == g.seen_count()
                assert f.fiducials == [r.__class__(**{**r.__dict__, 'model': near.models[
                    r.model.index]}) for r in g.fiducials], step
                seen += len(f.fiducials)
    assert skipped == STEPS * robots and seen > 0
    near.fiducial_index.begin_step()        # the next step's start
    later = [f for f in finders if f._seen is not None]
    assert later
    with pytest.raises(RuntimeError, match='a step later'):
        later[0].seen_count()


def test_the_rays_and_the_finders_together_read_as_apart(tmp_path, monkeypatch):
    """sensing.sense: a step's rays and finders in one parallel region give the bits of the
    two kernels apart, each in this thread (each thread takes every other ray and
    finder)."""
    if numba_threads() < 2:
        pytest.skip('one numba thread: the rays and finders are never together')
    path = flocking_world(tmp_path, 34, 7, 0.7)
    together, apart = load_world(path, seed=5, stageros=False), load_world(path, seed=5,
                                                                          stageros=False)
    calls = []
    joint = sensing._cast_and_find
    monkeypatch.setattr(sensing, '_cast_and_find', lambda *a: calls.append(1) or joint(*a))
    monkeypatch.setattr(sensing, 'TOGETHER_WORK', 1)
    finders = [m for m in apart.models if isinstance(m, fiducial_module.Fiducial)]
    for step in range(STEPS):
        together.step()
        with monkeypatch.context() as m:
            m.setattr(sensing, 'TOGETHER_WORK', 10 ** 9)
            m.setattr(sensing, 'PARALLEL_CANDIDATES', 10 ** 9)
            apart.step()
        assert_same(snapshot(together), snapshot(apart), step)
        assert [together.models[f.index].nearest() for f in finders] == [
            f.nearest() for f in finders], step
    assert len(calls) == STEPS


def test_your_own_controller_in_the_world_makes_every_finder_make_all_its_readings(
        tmp_path, monkeypatch):
    """A controller of your own may read any finder at any time: with one in the world no
    finder skips a ray, whatever its controller says."""
    (tmp_path / 'mine.py').write_text('def init(model, args):\n    model.subscribe()\n')
    monkeypatch.setenv('STAGEPATH', str(tmp_path))
    path = flocking_world(tmp_path, 6, 3, 0.9)
    with open(path, 'a') as f:
        f.write('model( name "own" pose [ 2.5 2.5 0 0 ] size [ 0.2 0.2 0.2 ] ctrl "mine" )\n')
    w = load_world(path, seed=5, stageros=False)
    assert not w.fiducial_index.nearest_only_allowed
    w.step()
    finders = [m for m in w.models if isinstance(m, fiducial_module.Fiducial)]
    # each update made its count of readings (-1: the nearest alone)
    assert finders and all(f.nearest_only and f._seen[0].count[f._seen[1]] >= 0
                           for f in finders)
    assert load_world(flocking_world(tmp_path, 6, 3, 0.9), stageros=False
                      ).fiducial_index.nearest_only_allowed


def test_the_noise_kernel_draws_as_the_beams_one_by_one():
    """RangerNoise.apply_rows (many sensors' beams in one kernel, the stream's pointers in
    registers) leaves the beams, the stream and the Gaussian's spare as the plain path, beam
    by beam (angle_noise, then range_noise: the angular-noise scans' draws), in the rows'
    order."""
    from stage_lite.model.glibc_random import Random
    from stage_lite.model.noise import RangerNoise
    gen = np.random.default_rng(7)
    counts = gen.integers(1, 6, 40)
    offsets = np.concatenate(([0], np.cumsum(counts))).astype(np.int64)
    rmax = gen.uniform(1.0, 3.0, 40)
    prop = gen.uniform(0.0, 0.1, 40)
    const = gen.uniform(0.0, 0.05, 40)
    ranges = gen.uniform(0.0, 3.5, int(offsets[-1]))      # hits and misses
    rows = gen.permutation(40).astype(np.int64)
    each, at_once = RangerNoise(Random(5)), RangerNoise(Random(5))
    expected = ranges.copy()
    for i in rows.tolist():
        for t in range(offsets[i], offsets[i + 1]):
            each.angle_noise()
            expected[t] = each.range_noise(ranges[t], rmax[i], (const[i], prop[i], 0.0))
    got = ranges.copy()
    at_once.apply_rows(got, offsets, rows, rmax, prop, const)
    assert got.tobytes() == expected.tobytes()
    for mine, theirs in zip(at_once.random.state(), each.random.state(), strict=True):
        assert mine.tobytes() == theirs.tobytes()
    assert at_once.spare.tobytes() == each.spare.tobytes()
