"""Robots far apart moved two at a time (stage_lite.model.motion's plan_apart and move_apart):
the same poses, stalls, readings and grid as moving them in turn, and the rule that splits
them."""
import numpy as np
from stage_lite import swarm_world
from stage_lite.model import motion
from stage_lite.model import space as space_mod
from stage_lite.model.world import load_world


def grid_lists(space):
    """Every cell's list of moving bodies, in both layers: (layer, region x, region y, cell)
    -> [(block, drawing number)], in list order; and the regions' counts, by region."""
    lists = {}
    for reg in np.flatnonzero(space.reg_dyn >= 0).tolist():
        page = space.reg_dyn[reg]
        ry, rx = divmod(reg, space.nrx)
        for layer in (0, 1):
            heads = space.dyn_head[page, layer]
            for cell in np.flatnonzero(heads >= 0).tolist():
                e, entries = heads[cell], []
                while e >= 0:
                    entries.append((int(space.ent_block[e]), int(space.ent_seq[e])))
                    e = space.ent_next[e]
                lists[(layer, rx + space.rx0, ry + space.ry0, cell)] = entries
    counts = {}
    for reg in np.flatnonzero(space.reg_count).tolist():
        ry, rx = divmod(reg, space.nrx)
        counts[(rx + space.rx0, ry + space.ry0)] = (int(space.reg_count[reg]),
                                                     int(space.reg_dyncount[reg]))
    return lists, counts


def run(path, steps, monkeypatch, apart, drive=None):
    """The world's steps with the robots moved in turn, or two at a time whenever a split
    exists (whatever numba's thread count); per step what a user sees, and the sides' sizes
    of each step moved apart. drive(world): commands given after the load."""
    monkeypatch.setattr(motion, 'APART_CELLS', 1 if apart else 10 ** 9)
    monkeypatch.setattr(motion, 'numba_threads', lambda: 2)
    w = load_world(path, stageros=drive is not None)
    if drive is not None:
        drive(w)
    sides = []
    plan = w.motion._move_apart

    def spied(*args):
        rest = plan(*args)
        if rest is not w.motion.in_order:
            sides.append((int(w.motion.side_len[0]), int(w.motion.side_len[1]), len(rest)))
        return rest
    w.motion._move_apart = spied
    seen = []
    for _ in range(steps):
        w.step()
        seen.append((w.state.pose.copy(), w.state.stalled.copy(), w.state.twist.copy(),
                     w._beam_ranges.copy(), w.space.seq))
    return w, seen, sides


def same_runs(path, steps, monkeypatch, drive=None):
    """Both runs, held equal step by step and in the grid at the end: the run in turn
    (its world and steps) and the sides of the run apart."""
    in_turn, seen_in_turn, none = run(path, steps, monkeypatch, False, drive)
    apart, seen_apart, sides = run(path, steps, monkeypatch, True, drive)
    assert none == []
    for k, (a, b) in enumerate(zip(seen_in_turn, seen_apart, strict=True)):
        for x, y in zip(a[:4], b[:4], strict=True):
            assert np.array_equal(x, y), 'step %d differs' % k
        assert a[4] == b[4]
    lists, counts = grid_lists(apart.space)
    assert (lists, counts) == grid_lists(in_turn.space)
    # each cell's list in drawing order: the ray walk takes its first entry in the way
    assert all([seq for _, seq in entries] == sorted(seq for _, seq in entries)
               for entries in lists.values())
    return in_turn, seen_in_turn, sides


def test_a_swarm_moved_two_at_a_time_is_the_swarm_moved_in_turn(tmp_path, monkeypatch):
    # 300 swarmbots a quarter of a metre apart, their controllers reading their rangers:
    # neighbours share the grid's regions, and the page pool grows from one page meanwhile
    monkeypatch.setattr(space_mod, 'PAGES_AT_START', 1)
    path = swarm_world.write_worlds(str(tmp_path), (300,))[300]
    _, _, sides = same_runs(path, 40, monkeypatch)
    assert len(sides) >= 15           # (packed at first, they are too close to split)
    left, right, rest = np.array(sides).T
    assert (left > 50).all() and (right > 50).all() and rest.max() > 0


CROWD = '''resolution 0.02
model( pose [ 0 0 0 0 ] size [ 9 7 0.5 ] bitmap "box.pgm" )
%s
'''


def test_a_crowd_bumping_into_each_other_moves_as_it_would_in_turn(tmp_path, monkeypatch):
    # 140 robots 0.6 m apart in a walled box, each driving and turning its own way: they
    # run into each other and into the walls within a few steps
    (tmp_path / 'box.pgm').write_bytes(b'P5 3 3 255\n' + bytes([0, 0, 0, 0, 255, 0, 0, 0, 0]))
    places = [(-3.9 + 0.6 * c, -2.7 + 0.6 * r) for r in range(10) for c in range(14)]
    path = tmp_path / 'crowd.world'
    path.write_text(CROWD % '\n'.join('position( pose [ %.2f %.2f 0 %d ] size [ 0.3 0.3 0.2 ] )'
                                      % (x, y, 37 * k % 360) for k, (x, y) in enumerate(places)))
    turns = np.random.default_rng(5).uniform(-1.0, 1.0, len(places))

    def drive(world):
        for k, turn in enumerate(turns.tolist()):
            world.set_command(k, 0.5, 0.0, turn)
    monkeypatch.setattr(space_mod, 'PAGES_AT_START', 1)
    _, seen, sides = same_runs(str(path), 20, monkeypatch, drive)
    stalls = [int(stalled.sum()) for _, stalled, _, _, _ in seen]
    assert stalls[0] < 20 and stalls[-1] > 100 and len(sides) >= 15   # stalling as they go


ROW = '''resolution 0.02
model( pose [ 0 2 0 0 ] size [ 20 0.2 0.5 ] )
%s
'''


def test_robots_leaving_the_table_or_meeting_head_on_move_as_they_would_in_turn(
        tmp_path, monkeypatch):
    # a row of robots two by two driving at each other, under a wall some of them turn
    # into; a second row driving off east, out of the grid's region table (it grows)
    robots = []
    for i in range(40):
        x = -10.0 + 0.5 * i
        robots.append('position( pose [ %.2f 1.8 0 %d ] size [ 0.3 0.3 0.2 ] )'
                      % (x, 0 if i % 2 == 0 else 180))
        robots.append('position( pose [ %.2f -3 0 0 ] size [ 0.3 0.3 0.2 ] )' % x)
    path = tmp_path / 'row.world'
    path.write_text(ROW % '\n'.join(robots))
    table = load_world(str(path)).space.nrx

    def drive(world):
        for k in range(len(world.robots)):
            world.set_command(k, 1.0 if k % 2 else 0.4, 0.0, 0.0 if k % 2 else 0.3)
    in_turn, seen, sides = same_runs(str(path), 60, monkeypatch, drive)
    assert in_turn.space.nrx > table and seen[-1][1].any()
    assert len(sides) >= 50


def sides_of(cells, draws=None, axis=0, split=0):
    cells = np.array(cells, np.int64)
    n = len(cells)
    boxes = cells >> 5
    draws = np.ones(n, np.bool_) if draws is None else np.array(draws, np.bool_)
    area = int(((boxes[:, 2] - boxes[:, 0] + 1) * (boxes[:, 3] - boxes[:, 1] + 1)).sum())
    rx0, ry0, nrx, nry = -4, -4, 8, 8
    head = np.full(nrx * nry, -1, np.int64)
    side = np.empty(n, np.int64)
    weights = motion._sides(cells, boxes, draws, np.arange(1, n + 1, dtype=np.int64), axis,
                            split, head, np.empty(area, np.int64), np.empty(area, np.int64),
                            np.empty(area, np.int64), rx0, ry0, nrx, side)
    assert (head == -1).all()       # left empty for the next split tried
    return side.tolist(), weights


def test_a_robot_whose_cells_may_meet_an_earlier_robot_of_the_rest_moves_after_it():
    # regions of 32 cells; the split between regions -1 and 0 (x = 0)
    before = (-20, 0, -12, 8)        # left, meets the straddler's cells, before it: moves first
    across = (-10, 0, 10, 8)         # across the split: the rest
    after_meeting = (-14, 4, -9, 9)  # left, meets it, after it: must wait for it
    after_apart = (-30, 20, -22, 28)  # left, the straddler's region but not its cells
    right = (40, 0, 50, 8)
    still = (60, 60, 62, 62)         # does not draw: the rest, whatever its cells
    side, weights = sides_of([before, across, after_meeting, after_apart, right, still],
                             draws=[1, 1, 1, 1, 1, 0])
    assert side == [0, 2, 2, 0, 1, 2]
    assert weights == (1 + 4, 5, 2 + 3)          # the rest's weight counts robots that draw
    # the rest's robots meeting in chains, in order: each one after one of the rest
    chain = [(-10, 0, 10, 8), (-14, 6, -9, 12), (-18, 10, -13, 16), (-40, 10, -33, 16)]
    assert sides_of(chain)[0] == [2, 2, 2, 0]


def test_plan_apart_leaves_moves_off_the_table_in_turn_and_asks_for_the_pages_it_needs(
        tmp_path):
    path = tmp_path / 'two.world'
    path.write_text('resolution 0.02\n' + '\n'.join(
        'position( pose [ %d 0 0 0 ] size [ 0.3 0.3 0.2 ] )' % x for x in (-3, 3)))
    w = load_world(str(path))
    for k in range(2):
        w.set_command(k, 0.5, 0.0, 0.0)
    w.step()
    m, sp = w.motion, w.space
    subscribed = w._masks()[0]

    regions = sp.nrx * sp.nry
    head, marked = np.full(regions, -1, np.int64), np.zeros(regions, np.bool_)

    def plan():
        pinned = np.empty(regions + 1, np.int64)
        k = motion.plan_apart(subscribed, w.state.velocity, w.state.pose, 0.1, 0,
                              *m._tables(), m.new_rows[0], sp.blk_radius, sp.ppm,
                              sp.rc_start, sp.rc_len, sp.rc_x, sp.rc_y, sp.rx0, sp.ry0,
                              sp.nrx, sp.nry, sp.reg_dyn, sp.reg_dyncount, sp.dyn_head,
                              sp.free_state, sp.page_free, m.sides, m.side_len, m.rest,
                              head, marked, pinned)
        assert (head == -1).all() and not marked.any()      # left for the next plan
        return k, pinned[:np.argmax(pinned < 0)] if k >= 0 else None

    # the east robot put where its regions hold nothing yet: its sides' regions get pages
    w.state.pose[1, 0] = 4.5
    counts, pages = sp.reg_dyncount.copy(), sp.reg_dyn.copy()
    k, held = plan()
    assert k == 0 and m.side_len.tolist() == [1, 1] and m.sides[:, 0].tolist() == [0, 1]
    assert (sp.reg_dyncount[held] == counts[held] + 1).all() and (sp.reg_dyn[held] >= 0).all()
    missing = int((pages[held] < 0).sum())
    assert missing > 0
    motion.unpin(np.append(held, -1), sp.reg_dyn, sp.reg_dyncount, sp.free_state,
                 sp.page_free)
    assert np.array_equal(sp.reg_dyncount, counts) and np.array_equal(sp.reg_dyn, pages)
    # a pool short of pages: how many more it needs, and nothing held
    free = int(sp.free_state[0])
    sp.free_state[0] = 0
    assert plan()[0] == -2 - missing
    assert np.array_equal(sp.reg_dyncount, counts) and np.array_equal(sp.reg_dyn, pages)
    sp.free_state[0] = free
    # a step from the table's east edge: every robot moved in turn
    w.state.pose[1, 0] = (sp.rx0 + sp.nrx) * 32 / sp.ppm - 0.2
    assert plan()[0] == -1
