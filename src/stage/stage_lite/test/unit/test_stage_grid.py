"""Stage's grid and ray walk (stage_lite.model.grid and .raytrace, through small worlds): outlines
drawn as 4-connected lines, the quirks Stage's rays have, and what a beam sees."""
import math

import numpy as np
import pytest
from stage_lite.model import grid, raytrace
from stage_lite.model.world import load_world

ONE_BEAM = 'define beam ranger ( sensor( range [ 0 5 ] samples 1 ) )\n'


def cells(vx, vy):
    vx, vy = np.array(vx, np.int64), np.array(vy, np.int64)
    n = grid.poly_cell_count(vx, vy)
    xs, ys = np.empty(n, np.int64), np.empty(n, np.int64)
    assert grid.poly_cells(vx, vy, xs, ys, 0) == n
    return list(zip(xs.tolist(), ys.tolist(), strict=True))


def test_outline_cells_leave_out_each_edge_last_cell():
    assert cells([0, 3, 3, 0], [0, 0, 2, 2]) == [
        (0, 0), (1, 0), (2, 0), (3, 0), (3, 1), (3, 2), (2, 2), (1, 2), (0, 2), (0, 1)]


def test_a_slanted_edge_is_a_4_connected_line():
    # Cohen's walk from (0, 0) to (2, 1): x, then y, then x; (2, 1) belongs to the next edge
    assert cells([0, 2], [0, 1])[:3] == [(0, 0), (1, 0), (1, 1)]


@pytest.mark.parametrize('a, b, expected', [(7, 32, 0), (-7, 32, 0), (-40, 32, -1),
                                            (40, 32, 1)])
def test_c_division_truncates(a, b, expected):
    assert raytrace.c_div(a, b) == expected


def world(tmp_path, body, robot):
    p = tmp_path / 'w.world'
    p.write_text('resolution 0.02\n' + ONE_BEAM + body + '\nposition( size [ 0.2 0.2 0.2 ] '
                 + robot + ' beam( ) )\n')
    w = load_world(str(p))
    w.step()
    return w.robots[0].rangers[0]


def test_rays_look_cells_up_by_truncation_toward_zero(tmp_path):
    # STAGE_TRUNCATED_LOOKUP. A wall's near edge is drawn in cell column 100 (x = 2.0 to
    # 2.02); a beam going north at x = 2.005 lies in that column and meets the wall's bottom
    # edge at y = 1.0. Mirrored to x < 0 the wall's near edge is column -100 (floor(-100.0))
    # and the beam at x = -2.005 lies in it, but Stage reads column trunc(-100.25) = -100...
    # so it hits too; at x = -1.995 (column -100 by floor) Stage reads -99 and misses.
    east = world(tmp_path, 'model( pose [ 2.5 1.25 0 0 ] size [ 1.0 0.5 1 ] )',
                 'pose [ 2.005 0.01 0 90 ]')
    assert east.ranges[0] == pytest.approx(1.0, abs=1e-12)
    west_inside = world(tmp_path, 'model( pose [ -2.5 1.25 0 0 ] size [ 1.0 0.5 1 ] )',
                        'pose [ -2.005 0.01 0 90 ]')
    assert west_inside.ranges[0] == pytest.approx(1.0, abs=1e-12)
    west_edge = world(tmp_path, 'model( pose [ -2.5 1.25 0 0 ] size [ 1.0 0.5 1 ] )',
                      'pose [ -1.995 0.01 0 90 ]')
    assert west_edge.ranges[0] == 5.0 and west_edge.intensities[0] == 0.0


def test_range_is_the_walk_position_not_the_exact_distance(tmp_path):
    # STAGE_WALK_RANGE: the beam starts in the middle of its cell (x = 0.01: 0.5 cell) and is
    # stopped in the middle of the wall's first cell: 0.5 m to a wall at x = 0.5, not 0.49 m
    near = world(tmp_path, 'model( pose [ 0.75 0 0 0 ] size [ 0.5 2 1 ] )',
                 'pose [ 0.01 0.01 0 0 ]')
    assert near.ranges[0] == 0.5 and near.intensities[0] == 1.0


def test_beams_jump_empty_regions_from_border_to_border(tmp_path):
    # STAGE_EMPTY_REGION_JUMP: regions of 32 x 32 cells; past the robot's own region the
    # beam jumps through empty ones to their borders (x = 64, 96 cells) and walks on from
    # there: it meets the wall's cell 100 at x = 100 cells, 99.5 cells from its start
    far = world(tmp_path, 'model( pose [ 2.25 0 0 0 ] size [ 0.5 2 1 ] )',
                'pose [ 0.01 0.01 0 0 ]')
    assert far.ranges[0] == np.float32(1.99)


@pytest.mark.parametrize('props, seen, intensity', [
    ('ranger_return 0', True, 0.0), ('ranger_return -1', False, 0.0),
    ('ranger_return 0.5', True, 0.5), ('obstacle_return 0', True, 1.0)])
def test_ranger_return(tmp_path, props, seen, intensity):
    g = world(tmp_path, 'model( pose [ 2.25 0 0 0 ] size [ 0.5 2 1 ] %s )' % props,
              'pose [ 0.01 0.01 0 0 ]')
    assert (g.ranges[0] < 5.0) == seen and g.intensities[0] == intensity


@pytest.mark.parametrize('wall_z, seen', [('0.2', False), ('0.22', True), ('1', True)])
def test_beams_meet_bodies_whose_height_holds_them(tmp_path, wall_z, seen):
    # the beam leaves at the body's height (0.2) plus half the transducer's (0.01):
    # 0.21000000000000002 in doubles, above a 0.21 m wall
    g = world(tmp_path, 'model( pose [ 2.25 0 0 0 ] size [ 0.5 2 %s ] )' % wall_z,
              'pose [ 0.01 0.01 0 0 ]')
    assert (g.ranges[0] < 5.0) == seen


def test_ray_angles_are_rounded_to_floats_one_after_the_other():
    out = np.zeros(3)
    raytrace.sample_angles(0.1, 0.25, 3, out, 0)
    a0 = float(np.float32(0.1))
    a1 = float(np.float32(a0 + 0.25))
    assert out.tolist() == [a0, a1, float(np.float32(a1 + 0.25))]
    assert out[0] != 0.1


def test_a_beam_through_empty_space_reads_its_range(tmp_path):
    g = world(tmp_path, 'model( pose [ 40 40 0 0 ] size [ 1 1 1 ] )', 'pose [ 0 0 0 33 ]')
    assert g.ranges[0] == 5.0 and not math.isnan(g.ranges[0])


@pytest.mark.parametrize('to, expected', [
    ((0.5, 0.0, 0.0, 0.0), 'free'),          # into open space
    ((1.2, 0.0, 0.0, 0.0), 'robot'),         # into the other robot
    ((-0.5, 1.85, 0.0, 0.3), 'wall'),        # into the wall
    ((0.0, -0.4, 0.0, 0.6), 'free')])        # under the high box (no height in common)
def test_a_move_tests_its_blocks_as_it_draws_them_as_collides_would_after(tmp_path, to,
                                                                          expected):
    # grid.move tests each block while drawing it; collides() walks the drawn cells after:
    # the same answer (the first hit in block, cell and list order)
    text = ('resolution 0.02\n'
            'position( name "me" pose [ 0 0 0 0 ] size [ 0.5 0.4 0.3 ]'
            ' block( points 3 point[0] [ 0 0 ] point[1] [ 0.3 0.1 ] point[2] [ 0 0.3 ]'
            ' z [ 0 0.2 ] ) )\n'
            'position( name "you" pose [ 1.6 0 0 0 ] size [ 0.6 0.6 0.3 ] )\n'
            'model( name "wall" pose [ 0 2 0 0 ] size [ 4 0.1 1 ] )\n'
            'model( name "high" pose [ 0 -0.6 0.35 0 ] size [ 0.4 0.2 0.1 ] )\n')
    answers = []
    for way in ('move', 'draw, then collides'):
        path = tmp_path / ('w_%d.world' % len(answers))
        path.write_text(text)
        w = load_world(str(path))
        r = w.robots[0]
        old = w._body_rows(r)
        r.model.pose = to
        new = w._body_rows(r)
        seqs = np.array([w._seqs(r), w._seqs(r)])
        if way == 'move':
            answers.append(w.space.move(r.block_ids, new, old, seqs, 0))
        else:
            w.space.draw(r.block_ids, new, 0, seqs[0])
            answers.append(w.space.collides(r.block_ids, 0))
    names = {w.robots[1].model.index: 'robot', grid.STATIC: 'wall', grid.NO_HIT: 'free'}
    assert answers[0] == answers[1]
    assert names.get(answers[0]) == expected


def cell_lists(space, layer):
    """Every cell's list of moving blocks in `layer`, head to tail ({(page, cell): [block]}),
    its backward links checked on the way: each entry's previous is the one before it, the
    head's is the tail."""
    lists = {}
    for page in space.reg_dyn[space.reg_dyn >= 0].tolist():
        for cell in range(grid.REGION_CELLS):
            head = int(space.dyn_head[page, layer, cell])
            if head < 0:
                continue
            order, e = [], head
            while e >= 0:
                if order:
                    assert space.ent_prev[e] == order[-1]
                order.append(e)
                e = int(space.ent_next[e])
            assert space.ent_prev[head] == order[-1]
            lists[(page, cell)] = [int(space.ent_block[x]) for x in order]
    return lists


def crowd(tmp_path, count, size):
    """A world of `count` square bodies of side `size` on one spot, drawn in turn."""
    path = tmp_path / 'crowd.world'
    path.write_text('resolution 0.02\n' + ''.join(
        'position( name "r%d" pose [ 0 0 0 0 ] size [ %g %g 0.3 ] )\n' % (k, size, size)
        for k in range(count)))
    return load_world(str(path))


@pytest.mark.parametrize('redrawn', [0, 1, 2])     # the head, the middle, the tail
def test_a_redrawn_block_leaves_its_cells_lists_and_joins_them_at_the_end(tmp_path, redrawn):
    # three bodies on one spot share every cell, drawn in turn; one drawn again (erased,
    # then drawn after the others) must leave the others' order as it was and come last
    w = crowd(tmp_path, 3, 0.4)
    space = w.space
    blocks = [int(r.block_ids[0]) for r in w.robots]
    layer = 0
    before = cell_lists(space, layer)
    assert before and all(order == blocks for order in before.values())
    r = w.robots[redrawn]
    space.draw(r.block_ids, w._body_rows(r), layer, w._seqs(r))
    after = cell_lists(space, layer)
    others = [b for b in blocks if b != blocks[redrawn]]
    assert set(after) == set(before)
    assert all(order == others + [blocks[redrawn]] for order in after.values())


def test_a_crowd_erased_leaves_empty_lists_and_frees_its_pages(tmp_path):
    # forty bodies on one spot: their cells' lists are forty long; erasing them all, one by
    # one in an order that takes heads, tails and middles, must empty every list and give
    # every page back
    w = crowd(tmp_path, 40, 0.3)
    space = w.space
    assert max(len(order) for order in cell_lists(space, 0).values()) == 40
    held = int((space.reg_dyn >= 0).sum())
    free_before = int(space.free_state[0])
    first = [20, 0, 39, 5, 38, 1]
    for k in first + [k for k in range(40) if k not in first]:
        b = int(w.robots[k].block_ids[0])
        for layer in (0, 1):
            grid.unmap_block(b, layer, space.rc_start, space.rc_len, space.rc_x, space.rc_y,
                             space.rx0, space.ry0, space.nrx, space.nry, space.reg_count,
                             space.reg_dyn, space.reg_dyncount, space.dyn_head,
                             space.ent_next, space.ent_prev, space.free_state,
                             space.page_free)
            assert all(b not in order for order in cell_lists(space, layer).values())
    assert cell_lists(space, 0) == {} and cell_lists(space, 1) == {}
    assert held > 0 and int(space.free_state[0]) == free_before + held
    assert (space.reg_dyn < 0).all() and (space.reg_dyncount == 0).all()


def test_a_beam_into_a_pile_sees_the_body_drawn_first(tmp_path):
    # three bodies on one spot, each returning its own intensity: the beam's reading names
    # the one drawn first, and once that one is drawn again, the next
    path = tmp_path / 'pile.world'
    path.write_text('resolution 0.02\n' + ONE_BEAM + ''.join(
        'position( name "r%d" pose [ 1 0 0 0 ] size [ 0.4 0.4 1.0 ] ranger_return %d )\n'
        % (k, k + 1) for k in range(3))
        + 'position( name "eye" pose [ 0 0 0 0 ] size [ 0.1 0.1 0.2 ] beam( ) )\n')
    w = load_world(str(path))
    eye = w.robots[3].rangers[0]
    w.step()
    assert eye.ranges[0] == pytest.approx(0.8, abs=0.03) and eye.intensities[0] == 1.0
    r = w.robots[0]
    for layer in (0, 1):
        w.space.draw(r.block_ids, w._body_rows(r), layer, w._seqs(r))
    w.step()
    assert eye.intensities[0] == 2.0
