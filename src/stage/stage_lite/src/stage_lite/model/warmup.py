"""Compile stage_lite's kernels once, ahead of the first stageros: `python3 -m
stage_lite.model.warmup` (./ws build runs it).

numba compiles the model's kernels (jit.py) at their first call and keeps them in its cache
(__pycache__ beside the sources, or NUMBA_CACHE_DIR); a stageros that finds them there
starts in a fraction of a second instead of a few seconds. A small world with a floor plan,
a body, a robot that moves into it, a camera, a fiducial finder and a blobfinder, two lasers
whose rays numba's threads share and one whose few rays are cast in the calling thread (with
angular noise, and Stage's lasernoise controller on it), Stage's wander on one robot and
expand_swarm and pioneer_flocking on two others (their batches' kernels) calls every kernel
with the argument types stageros uses (test_stage_warmup.py checks that none is left out);
a second world, whose robot stands on another model, the kernels a World moving its robots
one by one calls; a third, two robots far apart, the kernels that move robots two at a
time; fasr2's planner and its batch's kernel, and fasr's batches' kernels, are called on
their own.
"""
import glob
import hashlib
import os
import sys
import tempfile
import time

#: stage_lite's own folder: its sources, and numba's cache beside them
PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STAMP = 'kernels.sha256'

# lasers with enough beams for the threads too (space.PARALLEL_RAYS), and one with a few;
# a ring of 12 one-beam sensors for Stage's expand_swarm and pioneer_flocking (their batches)
RING = 'ranger( %s )' % ' '.join(
    'sensor( pose [ 0 0 0 %d ] range [ 0 2 ] fov 30 samples 1 )' % (30 * k) for k in range(12))
WORLD = '''resolution 0.02
define laser ranger ( sensor( range [ 0 5 ] fov 180 samples %d ) )
define short_laser ranger ( sensor( range [ 0 5 ] fov 180 samples 5 noise [ 0.01 0.01 1 ] )
                           ctrl "lasernoise" )
model( bitmap "plan.pgm" size [ 2 2 0.5 ] pose [ 0 0 0 10 ] )
model( pose [ 0.6 0 0 0 ] size [ 0.1 0.3 0.5 ] fiducial_return 1 )
position( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.2 ] laser( ) fiducial( ) blobfinder( ) )
position( pose [ -0.6 0 0 0 ] size [ 0.3 0.3 0.2 ] laser( ) camera( resolution [ 8 6 ] )
          ctrl "wander" )
position( pose [ 0 -0.6 0 0 ] size [ 0.3 0.3 0.2 ] short_laser( ) )
position( pose [ 0.6 0.6 0 0 ] size [ 0.1 0.1 0.1 ] %s ctrl "expand_swarm" )
position( pose [ -0.6 0.6 0 0 ] size [ 0.1 0.1 0.1 ] fiducial_return 2 %s fiducial( )
          ctrl "pioneer_flocking" )
'''


# a robot on a table: the World moves it robot by robot (world.World._step_each)
ON_A_MODEL = '''resolution 0.02
model( pose [ 0 0 0 0 ] size [ 0.6 0.6 0.1 ] position( size [ 0.2 0.2 0.2 ] ) )
'''

# two robots far apart: moved at once, each in its own thread (motion.Motion._move_apart)
APART = '''resolution 0.02
position( pose [ -3 0 0 0 ] size [ 0.3 0.3 0.2 ] )
position( pose [ 3 0 0 0 ] size [ 0.3 0.3 0.2 ] )
'''


def warm():
    """Loads and steps the world: every kernel compiled (or loaded from the cache)."""
    import numpy as np

    from .space import PARALLEL_RAYS
    from .world import load_world
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, 'plan.pgm'), 'wb') as f:
            f.write(b'P5 4 4 255\n' + bytes([0] * 4 + [255, 0, 255, 255] + [255] * 4 + [0] * 4))
        path = os.path.join(tmp, 'warm.world')
        with open(path, 'w') as f:
            f.write(WORLD % (PARALLEL_RAYS, RING, RING))
        world = load_world(path)
        world.set_command(0, 1.0, 0.0, 0.0)
        for _ in range(6):
            world.step()
        for robot in (world.robots[0], world.robots[2]):   # the threads', then this one's
            world.scan_from(robot.rangers[0], robot.model.pose)
        world.cast_rays(np.array([1, 0], np.int64))    # some of the sensors (Stage's `stage`)
        world.occupancy()
        warm_sensors(world)
        warm_chargers(world)
        path = os.path.join(tmp, 'on_a_model.world')
        with open(path, 'w') as f:
            f.write(ON_A_MODEL)
        world = load_world(path)
        world.set_command(0, 0.1, 0.0, 0.1)
        for _ in range(2):
            world.step()
        path = os.path.join(tmp, 'apart.world')
        with open(path, 'w') as f:
            f.write(APART)
        warm_moves_apart(load_world(path))
    warm_planner()
    warm_fasr()
    warm_race()


def warm_moves_apart(world):
    """The moves of robots far apart, two at a time (motion.move_work, plan_apart, and
    move_robots without its checks), which a step takes only with many robots on a machine
    with two threads or more."""
    from .motion import move_work
    for k in range(len(world.robots)):
        world.set_command(k, 0.5, 0.0, 0.1)
    world.step()
    m, subscribed, layer = world.motion, world._masks()[0], world.updates % 2
    move_work(subscribed, world.state.velocity, m.r_blk_off, m.r_blocks, world.space.rc_len,
              layer)
    m._move_apart(world.state, subscribed, world.interval_us / 1e6, layer)


def warm_race():
    """The worker-thread race's clocks (race.py's kernels), as a threaded world's step
    calls them."""
    import numpy as np

    from .race import WorkerRace
    WorkerRace(2, 1, slot_beams=[1, 1], slot_robot=[0, 1], robot_blocks=[1, 1],
               move_order=[0, 1]).stale(np.array([1, 2]), np.array([0, 1]),
                                        np.array([True, True]))


def warm_planner():
    """fasr2's A* search, its plans' advice and its batch's kernel, with the types fasr2
    calls them with (one robot following a plan of one node)."""
    import numpy as np

    from stage_lite.controllers._astar import astar
    from stage_lite.controllers._fasr2_batch import _work_all
    from stage_lite.controllers._fasr2_plans import Plan
    astar([1, 1, 9, 1], 2, 2, (0, 0), (1, 1))
    Plan([0.5], [0.5]).good_direction(0.0, 0.0)
    one, no = np.ones(1, np.bool_), np.zeros(1, np.bool_)
    ints, floats = np.zeros(1, np.int64), np.zeros(1)
    _work_all(ints, one, ints, ints, ints, ints.copy(), no, ints, np.zeros((1, 2)),
              np.ones((1, 2)), np.ones(1), floats, floats, np.array([0, 1]), np.ones(4),
              ints, np.array([4]), np.zeros((1, 4)), ints, np.zeros((1, 4)), ints.copy(),
              np.arange(31, dtype=np.int64), np.array([3, 0]), 0.7, 0.5, 0.05, 0.5, 10, 0.4,
              0.5, 5.0, 0.25)


def warm_fasr():
    """fasr's batches' kernels, with the types FasrBatch and FasrPositionBatch give them
    (one robot that starts an avoid, away from the source and the sink)."""
    import numpy as np

    from stage_lite.controllers._fasr_batch import _away_all, _work_all
    _away_all(np.zeros(1, np.int64), np.zeros((1, 4)), np.zeros(1, np.int64), -7.0, -7.0,
              2.0, 7.0, 7.0, 1.0)
    ints = np.zeros(1, np.int64)
    _work_all(ints, np.ones(1, np.bool_), ints.copy(), ints, np.zeros((2, 4, 4)),
              np.zeros(4), ints, np.array([4]), np.zeros((1, 4)), ints, np.zeros((1, 4)),
              ints.copy(), np.arange(31, dtype=np.int64), np.array([3, 0]), 0.7, 0.5, 0.05,
              0.5, 10, 0.4, 8, 4, 4)


def warm_chargers(world):
    """A charger's look for the moving blocks it touches, and the static chargers' look for
    any (energy.py's kernels), on the cells of the first robot's first block, with the
    types Energy.touching and Energy._quiet_chargers give them; and the packs'
    dissipations, as Energy.update calls them."""
    import numpy as np

    from .energy import Energy, _cells_hold_moving, _dissipate
    _dissipate(np.zeros(1, np.int64), np.ones(1), 0, 1, np.ones((1, 4)), 0.1)
    space = world.space
    layer = world.updates % 2
    k = world.robots[0].block_ids[0]
    cells = slice(space.rc_start[k], space.rc_start[k] + space.rc_len[layer, k])
    xs = np.ascontiguousarray(space.rc_x[layer, cells])
    ys = np.ascontiguousarray(space.rc_y[layer, cells])
    Energy._dynamic_in(space, xs, ys, layer, set())
    _cells_hold_moving(xs, ys, np.array([0, len(xs)], np.int64), layer, space.rx0, space.ry0,
                       space.nrx, space.nry, space.reg_dyn, space.dyn_head,
                       np.zeros(1, np.bool_))


def warm_sensors(world):
    """The fiducial finder's and the blobfinder's rays (sight.py's kernel), and the
    finders' kernel for many finders at once (the threads')."""
    from .fiducial import FiducialIndex
    from .sensing import PARALLEL_CANDIDATES, update_all
    from .sight import Sight
    sight = Sight(world.models, world.robots, world.space)
    index = FiducialIndex(world.models)
    layer = (world.updates + 1) % 2
    for m in world.models:
        if m.kind == 'fiducial':
            m.update(index, sight, layer)
            update_all([m] * (PARALLEL_CANDIDATES // len(index.models) + 1), index, sight,
                       layer)
        elif m.kind == 'blobfinder':
            m.update(sight, layer)


def drop_stale_kernels(package_dir=PACKAGE_DIR):
    """numba checks a cached kernel against its own source file only, and a kernel that
    calls another file's (motion.move_robots compiles grid.move into itself) would load
    stale from the cache once that file changed. So the cache is kept with one digest of
    every source of the package, and when the digest changes every cached kernel of the
    package goes (numba's cache beside the sources; one under NUMBA_CACHE_DIR is the user's
    to clear). Returns how many cache files went."""
    digest = hashlib.sha256()
    for path in sorted(glob.glob(os.path.join(package_dir, '**', '*.py'), recursive=True)):
        digest.update(os.path.relpath(path, package_dir).encode())
        with open(path, 'rb') as f:
            digest.update(hashlib.sha256(f.read()).digest())
    stamp = os.path.join(package_dir, '__pycache__', STAMP)
    try:
        with open(stamp) as f:
            if f.read().strip() == digest.hexdigest():
                return 0
    except OSError:
        pass
    gone = 0
    try:
        for pattern in ('*.nbi', '*.nbc'):
            for path in glob.glob(os.path.join(package_dir, '**', '__pycache__', pattern),
                                  recursive=True):
                os.remove(path)
                gone += 1
        os.makedirs(os.path.dirname(stamp), exist_ok=True)
        with open(stamp, 'w') as f:
            f.write(digest.hexdigest() + '\n')
    except OSError as err:      # a read-only install: numba keeps its cache elsewhere then
        sys.stderr.write('stage_lite: cannot renew the kernels\' cache: %s\n' % err)
    return gone


def main():
    start = time.monotonic()
    drop_stale_kernels()
    warm()
    sys.stdout.write('stage_lite: kernels ready (%.1f s)\n' % (time.monotonic() - start))


if __name__ == '__main__':
    main()
