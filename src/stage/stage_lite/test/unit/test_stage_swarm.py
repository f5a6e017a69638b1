"""Swarms: the generated swarm worlds, and the grid's page pool that grows with them."""
import math

import numpy as np
import pytest
from stage_lite import swarm_world
from stage_lite.model import space as space_mod
from stage_lite.model.world import load_world
from stage_lite.node.swarm_stageros import parse


def test_places_fill_the_hospitals_strip_tile_by_tile():
    one = swarm_world.places(1000)
    assert one[0] == (-59.0, -15.0) and one[4] == (-59.0, -14.0)
    assert one[5] == (-58.75, -15.0) and one[-1] == (-9.25, -14.0)
    ten = swarm_world.places(10000)
    assert len(ten) == len(set(ten)) == 10000
    cols, rows = swarm_world.tiles_grid(10000)
    assert cols * rows >= 10 and (cols, rows) == (2, 5)       # 280 m x 300 m: near square
    # every robot inside the floor, clear of its border wall
    w, h = cols * swarm_world.TILE_M[0], rows * swarm_world.TILE_M[1]
    xs, ys = np.array(ten).T
    assert np.abs(xs).max() < w / 2 - 1.0 and np.abs(ys).max() < h / 2 - 1.0


def test_a_swarm_world_loads_with_its_robots_and_controllers(tmp_path):
    path = swarm_world.write_worlds(str(tmp_path), (12,))[12]
    w = load_world(path, stageros=False)
    assert [r.model.token for r in w.robots] == ['r%d' % i for i in range(12)]
    assert all(len(r.model.children[0].sensors) == 12 for r in w.robots)
    start = w.state.pose[:, :2].copy()
    for _ in range(20):
        w.step()
    moved = np.hypot(*(w.state.pose[:, :2] - start).T)
    assert (moved > 0).sum() >= 10        # expand_swarm drives them (a few boxed in turn)

    def spread(xy):
        return np.hypot(*(xy - xy.mean(axis=0)).T).mean()
    assert spread(w.state.pose[:, :2]) > spread(start) + 0.05     # apart from each other


def test_no_swarm_without_a_robot(tmp_path):
    with pytest.raises(ValueError, match='at least one robot'):
        swarm_world.write_worlds(str(tmp_path), (0,))


def run(path, steps):
    w = load_world(path, stageros=False)
    for _ in range(steps):
        w.step()
    return w


def test_the_page_pool_grows_as_regions_fill_and_changes_nothing(tmp_path, monkeypatch):
    path = swarm_world.write_worlds(str(tmp_path), (200,))[200]
    monkeypatch.setattr(space_mod, 'PAGES_AT_START', 10 ** 9)     # the worst case at once
    roomy = run(path, 40)
    assert roomy.space.dyn_head.shape[0] == int(roomy.space.blk_pages.sum())
    monkeypatch.setattr(space_mod, 'PAGES_AT_START', 1)
    grown = run(path, 40)
    assert np.array_equal(grown.state.pose, roomy.state.pose)
    assert np.array_equal(grown.space.reg_dyncount, roomy.space.reg_dyncount)
    sp = grown.space
    pages = sp.dyn_head.shape[0]
    in_use = int((sp.reg_dyn >= 0).sum())
    # it grew from one page, far below the worst case (every block in as many regions as
    # its size allows, in both layers)
    assert pages > 1 and in_use == pages - int(sp.free_state[0])
    assert pages < int(sp.blk_pages.sum()) / 4
    # free pages are those no region holds, each once
    free = sp.page_free[:int(sp.free_state[0])]
    assert len(set(free.tolist())) == len(free)
    assert not set(free.tolist()) & set(sp.reg_dyn[sp.reg_dyn >= 0].tolist())


def test_the_page_pool_grows_by_a_quarter_and_keeps_every_page(tmp_path, monkeypatch):
    sp = run(swarm_world.write_worlds(str(tmp_path), (20,))[20], 0).space
    held = sp.dyn_head.copy()
    sizes = [sp.dyn_head.shape[0]]
    while sizes[-1] < 2000:
        sp.grow_pages()
        sizes.append(sp.dyn_head.shape[0])
    for have, now in zip(sizes[:-1], sizes[1:], strict=True):
        assert now - have == max(have // 4, space_mod.PAGES_GROWN_AT_LEAST)
    assert sizes[-1] < 2500             # doubling would have reached up to 4,000
    assert np.array_equal(sp.dyn_head[:held.shape[0]], held)
    assert (sp.dyn_head[held.shape[0]:] == -1).all()
    free = sp.page_free[:int(sp.free_state[0])].tolist()
    assert len(free) == len(set(free)) and set(range(held.shape[0], sizes[-1])) <= set(free)
    sp.grow_pages(1000)                 # what a plan needs at once comes at once
    assert sp.dyn_head.shape[0] == sizes[-1] + 1000
    # grown in place while nothing else holds the pool; copied while something does (a
    # kernel's arguments), which keeps what it holds intact
    pool = sp.dyn_head
    pool[0, 0, 0] = 7
    sp.grow_pages()
    assert sp.dyn_head is not pool and sp.dyn_head[0, 0, 0] == 7 == pool[0, 0, 0]
    assert pool.shape[0] == sizes[-1] + 1000
    del pool

    def no_copy(*args, **kwargs):
        raise AssertionError('the pool was copied, not grown in place')
    monkeypatch.setattr(np, 'full', no_copy)
    sp.grow_pages()
    assert sp.dyn_head[0, 0, 0] == 7 and (sp.dyn_head[-1] == -1).all()
    assert sp.dyn_head.flags.owndata and sp.dyn_head.flags.c_contiguous


def test_robots_started_inside_bodies_are_named_and_stay_put(tmp_path):
    text = swarm_world.world_text(5)
    head = text[:text.index('swarmbot( name "r0"')]
    # a pile of two, one across the wall's inner edge, one inside the 0.2 m wall clear of
    # its edges (Stage draws bodies by their outlines: it sees nothing there), one free
    robots = [(0.0, 0.0), (0.0, 0.0), (-69.8, 0.0), (-69.9, 10.0), (5.0, 5.0)]
    path = tmp_path / 'piled.world'
    path.write_text(head + ''.join('swarmbot( name "r%d" pose [ %.3f %.3f 0 0 ] )\n' % (i, x, y)
                                   for i, (x, y) in enumerate(robots)))
    w = load_world(str(path), stageros=False)
    assert w.warnings == ['%s: 3 of 5 robots start overlapping a wall or another body (the'
                          ' first: r0, on r1); as in Stage, they cannot move until it has'
                          ' moved away' % path]
    start = w.state.pose.copy()
    for _ in range(20):
        w.step()
    moved = np.abs(w.state.pose - start).max(axis=1) > 0
    assert moved.tolist() == [False, False, False, True, True]


def test_a_clear_swarm_loads_without_a_warning(tmp_path):
    path = swarm_world.write_worlds(str(tmp_path), (50,))[50]
    assert load_world(path, stageros=False).warnings == []


def test_the_ros_variant_gives_the_twelve_infrared_headings_as_one_sensor(tmp_path):
    path = swarm_world.write_worlds(str(tmp_path), (3,), ros=True)[3]
    assert path.endswith('swarm_ros_3.world')
    with open(path) as f:
        text = f.read()
    assert 'ctrl' not in text
    # the same floor and robots as the Stage swarm: only the robot's definition differs
    plain = swarm_world.world_text(3)
    assert text[text.index('swarmbot( name'):] == plain[plain.index('swarmbot( name'):]
    w = load_world(path, stageros=True)
    assert len(w.robots) == 3
    for robot in w.robots:
        assert len(robot.rangers) == 1
        r = robot.rangers[0]
        assert r.samples == 12 and r.range_max == 2.0
        lyaw = r.pose[3]
        headings = [math.degrees(lyaw + r.angle_min + i * r.angle_increment) % 360.0
                    for i in range(12)]
        # beam i looks along IR sensor i's heading, 30 i degrees
        assert headings == pytest.approx([30.0 * i for i in range(12)], abs=1e-9)
    w.step()
    assert all(np.all(r.rangers[0].ranges <= 2.0) for r in w.robots)


def test_swarm_stageros_arguments():
    assert parse(['-g', '100', '__name:=stageros']) == (
        ['-g'], 100, ['rosrun', 'stage_ros', 'stageros'], ['__name:=stageros'])
    assert parse(['--stageros', '/x/stageros', '5'])[2] == ['/x/stageros']
    for bad, error in ((['ten'], 'not a robot count'), (['0'], 'at least one'),
                       (['-g'], 'how many robots')):
        with pytest.raises(ValueError, match=error):
            parse(bad)
