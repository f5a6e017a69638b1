"""Stage's fasr (controllers/fasr.py): its tables, its beam rule, picking up and delivering
flags, and a hungry robot docking at a charger, charging, undocking and going back to work,
on a small world of the tests' own (worlds/fasr_small.world: a room, a source, a sink, a
charger, three robots)."""
import math
import os

import numpy as np
import pytest
from stage_lite.controllers import fasr
from stage_lite.model.stage_api import Flag
from stage_lite.model.world import load_world

WORLD = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'worlds',
                     'fasr_small.world')


@pytest.fixture
def world():
    return load_world(WORLD, stageros=False)


def named(w, name):
    return next(m for m in w.models if m.token == name)


def forager_of(w, model):
    """The controller's Forager behind the robot's update callback."""
    for callback, _, _ in w.scheduler.callbacks[(model, 'update')]:
        found = getattr(callback.function, '__self__', None)   # stage_api.ApiCallback
        if isinstance(found, fasr.Forager):
            return found
    raise LookupError(model.token)


@pytest.mark.parametrize('x, y, carrying, hungry, degrees', [
    (-7, -7, False, False, -120),     # NEED[0][0]
    (-7, -7, True, False, 90),        # HAVE[0][0]
    (7, 7, True, True, -90),          # REFUEL[3][3]
    (-3.9, 5, True, False, 45),       # (4.1 / 4, 13 / 4): column 1, row 3
    (-4.1, 5, True, False, 0),        # column 0
    (30, -30, False, False, 180),     # held to column 3, row 0: NEED[0][3]
    (-8.5, -8.5, False, True, 0),     # (-0.125) truncated toward zero: REFUEL[0][0]
])
def test_headings_come_from_the_tables_by_grid_cell(x, y, carrying, hungry, degrees):
    assert fasr.heading_goal(x, y, carrying, hungry) == pytest.approx(math.radians(degrees))


def test_the_front_is_the_middle_half_and_half_a_metre_stops_it():
    far = np.full(8, 3.0)
    for i, seen in [(2, False), (3, True), (5, True), (6, False)]:    # n/4 < i < n - n/4
        scan = far.copy()
        scan[i] = 0.69
        assert fasr.scan_rule(scan)[0] is seen, i
    scan = far.copy()
    scan[0] = 0.49
    assert fasr.scan_rule(scan) == (False, True, 3.0, 0.49)


def test_a_robot_at_the_source_takes_its_flag_after_20_updates(world):
    getter, source = named(world, 'getter'), named(world, 'source')
    for _ in range(20):
        world.step()
    assert (len(getter.flags), len(source.flags)) == (0, 1)
    world.step()                               # the 21st position update
    assert len(getter.flags) == 1
    for _ in range(30):                        # it carries its payload: no more
        world.step()
    assert len(getter.flags) == 1


def test_a_robot_at_the_sink_gives_it_its_flag_every_21_updates(world):
    putter, sink = named(world, 'putter'), named(world, 'sink')
    world.handle(putter).push_flag(Flag())
    for _ in range(20):
        world.step()
    assert len(sink.flags) == 0
    world.step()
    assert (len(putter.flags), len(sink.flags)) == (0, 1)
    for _ in range(21):                        # nothing to give: the sink counts nothing
        world.step()
    assert len(sink.flags) == 0 + 1


def test_a_hungry_robot_docks_charges_undocks_and_goes_back_to_work(world):
    hungry = named(world, 'hungry')
    robot = forager_of(world, hungry)
    pack = hungry.power_pack
    modes = [robot.mode]
    charged_at = None
    for k in range(400):
        world.step()
        if robot.mode != modes[-1]:
            modes.append(robot.mode)
            if robot.mode == fasr.MODE_UNDOCK:
                assert pack.stored / pack.capacity > fasr.FULL
        if charged_at is None and pack.charging:
            charged_at = k
            assert robot.mode == fasr.MODE_DOCK and robot.charger_range < 0.5
    assert modes == [fasr.MODE_WORK, fasr.MODE_DOCK, fasr.MODE_UNDOCK, fasr.MODE_WORK]
    assert charged_at is not None
    assert robot.charger_range > 0.3           # backed off before going back to work
