"""Stage's energy model (energy.py): the power pack's arithmetic, the properties as Stage
reads them, what models draw, and chargers filling the packs of the models touching them."""
import pytest
from stage_lite.model.energy import PowerPack, _dynamic_models, find_power_pack, position_watts
from stage_lite.model.world import load_world

ROOM = '''resolution 0.02
interval_sim 100
model( pose [ 0 0 0 0 ] size [ 10 10 0.5 ] boundary 1 noblocks 1 )
'''


def world(tmp_path, body, **kw):
    path = tmp_path / 'e.world'
    path.write_text(ROOM + body)
    return load_world(str(path), **kw)


def named(w, name):
    return next(m for m in w.models if m.token == name)


# ---- the pack ------------------------------------------------------------------------------
@pytest.mark.parametrize('stored, capacity, op, amount, after, charging', [
    (10.0, 100.0, 'add', 50.0, 60.0, True),
    (90.0, 100.0, 'add', 50.0, 100.0, True),          # no more than the capacity
    (100.0, 100.0, 'add', 50.0, 100.0, False),        # nothing added: not charging
    (10.0, 100.0, 'subtract', 4.0, 6.0, False),
    (10.0, 100.0, 'subtract', 40.0, 0.0, False),      # never below 0
    (-1.0, -1.0, 'subtract', 40.0, -1.0, False),      # an infinite supply keeps its store
])
def test_add_and_subtract_stay_within_the_pack(stored, capacity, op, amount, after, charging):
    p = PowerPack(stored, capacity)
    getattr(p, op)(amount)
    assert p.stored == pytest.approx(after, abs=1e-12)
    assert p.charging is charging


def test_transfer_is_bounded_by_the_store_and_by_what_the_other_can_take():
    src, dst = PowerPack(30.0, 100.0), PowerPack(0.0, 100.0)
    src.transfer_to(dst, 50.0)
    assert (src.stored, dst.stored) == (0.0, 30.0)
    src, dst = PowerPack(100.0, 100.0), PowerPack(90.0, 100.0)
    src.transfer_to(dst, 50.0)
    assert (src.stored, dst.stored) == (90.0, 100.0)
    infinite, dst = PowerPack(-1.0, -1.0), PowerPack(0.0, 100.0)
    infinite.transfer_to(dst, 50.0)
    assert (infinite.stored, infinite.supplied, dst.stored) == (-1.0, 50.0, 50.0)


def test_dissipation_counts_only_what_was_there_and_the_proportion_left():
    p = PowerPack(10.0, 40.0)
    assert p.proportion_remaining() == 0.25
    p.dissipate(4.0)
    p.dissipate(100.0)
    assert (p.stored, p.dissipated) == (0.0, 10.0)
    infinite = PowerPack(-1.0, -1.0)
    infinite.dissipate(7.0)
    assert (infinite.stored, infinite.dissipated, infinite.proportion_remaining()) == \
        (-1.0, 7.0, 1.0)


# ---- the properties --------------------------------------------------------------------------
@pytest.mark.parametrize('props, stored, capacity', [
    ('joules 100', 100.0, 100.0),
    ('joules 100 joules_capacity 300', 100.0, 300.0),
    ('joules_capacity 500 kjoules 2', 2000.0, 2000.0),      # kjoules after joules_capacity
    ('kjoules 2 kjoules_capacity 1', 1000.0, 1000.0),       # a smaller capacity cuts the store
    ('joules -1', -1.0, -1.0),                              # an infinite supply
])
def test_packs_are_read_in_stages_order_whatever_the_files_order(tmp_path, props, stored,
                                                                  capacity):
    w = world(tmp_path, 'model( name "m" pose [ 1 1 0 0 ] %s )\n' % props)
    p = named(w, 'm').power_pack
    assert (p.stored, p.capacity) == (stored, capacity)
    assert not w.warnings


def test_a_model_without_a_pack_draws_from_its_nearest_ancestors(tmp_path):
    w = world(tmp_path, 'position( name "r" kjoules 1 ranger( ) model( model( ) ) )\n')
    r = named(w, 'r')
    assert find_power_pack(r.children[1].children[0]) is r.power_pack
    assert find_power_pack(named(w, 'model:1')) is None   # Stage's first: model:1


# ---- drawing -----------------------------------------------------------------------------------
def test_a_robot_draws_by_its_commanded_speed_and_mass_its_ranger_by_sensors(tmp_path):
    w = world(tmp_path, 'position( name "r" pose [ -2 0 0 0 ] mass 10 kjoules 1\n'
                        '  velocity_bounds [ -1 1 0 0 0 0 -90 90 ]\n'
                        '  ranger( sensor( samples 3 ) sensor( samples 3 ) ) )\n')
    w.set_command(0, 0.5, 0.0, 3.0)          # turn above its bound: drawn all the same
    w.step()
    r = named(w, 'r')
    assert r.watts == pytest.approx(1.0 + 10.0 * 10.0 * 3.5) == position_watts(10, (0.5, 0, 0, 3))
    ranger = r.children[0]
    assert ranger.watts == pytest.approx(0.4)    # 0.2 W per sensor while started
    assert r.power_pack.stored == pytest.approx(1000.0 - (351.0 + 0.4) * 0.1, abs=1e-9)
    assert r.power_pack.dissipated == pytest.approx((351.0 + 0.4) * 0.1, abs=1e-9)


def test_an_empty_pack_stops_nothing(tmp_path):
    w = world(tmp_path, 'position( name "r" pose [ -2 0 0 0 ] mass 10 joules 5 )\n')
    w.set_command(0, 0.5, 0.0, 0.0)
    for _ in range(10):
        w.step()
    r = named(w, 'r')
    assert r.power_pack.stored == 0.0 and r.power_pack.dissipated == 5.0
    assert r.pose[0] == pytest.approx(-2.0 + 10 * 0.05)


def test_an_infinite_supply_gives_what_a_robot_draws_and_keeps_its_store(tmp_path):
    w = world(tmp_path, 'position( name "r" pose [ -2 0 0 0 ] mass 10 joules -1 )\n')
    w.set_command(0, 0.5, 0.0, 0.0)
    for _ in range(4):
        w.step()
    pack = named(w, 'r').power_pack
    drawn = 4 * position_watts(10, (0.5, 0, 0, 0)) * 0.1
    assert pack.stored == -1.0
    assert pack.supplied == pytest.approx(drawn) and pack.dissipated == pytest.approx(drawn)


def test_nothing_draws_until_it_is_started(tmp_path):
    w = world(tmp_path, 'position( name "r" pose [ -2 0 0 0 ] mass 10 joules 50 watts 3 )\n',
              stageros=False)
    for _ in range(5):
        w.step()
    assert named(w, 'r').power_pack.stored == 50.0


# ---- charging ------------------------------------------------------------------------------------
CHARGER = ('model( name "charger" pose [ 1 0 0 0 ] size [ 0.1 0.4 0.3 ] obstacle_return 0\n'
           '       joules %s give_watts %s alwayson 1 )\n')
TAKER = ('position( name "%s" pose [ %s 0 0 0 ] size [ 0.4 0.4 0.3 ] joules 100\n'
         '          joules_capacity 10000 take_watts %s )\n')


@pytest.mark.parametrize('give, take', [(2000, 300), (150, 300)])
def test_a_charger_fills_a_robot_touching_it_at_the_lesser_rate(tmp_path, give, take):
    w = world(tmp_path, CHARGER % (-1, give) + TAKER % ('near', 0.85, take)
              + TAKER % ('far', -2, take), stageros=False)
    for _ in range(5):
        w.step()
    near, far, charger = named(w, 'near'), named(w, 'far'), named(w, 'charger')
    assert near.power_pack.stored == pytest.approx(100.0 + 5 * min(give, take) * 0.1)
    assert near.power_pack.charging
    assert far.power_pack.stored == 100.0 and not far.power_pack.charging
    assert charger.power_pack.stored == -1.0           # an infinite supply
    assert charger.power_pack.supplied == pytest.approx(5 * min(give, take) * 0.1)


def test_a_finite_charger_gives_what_it_has_and_a_full_pack_takes_no_more(tmp_path):
    w = world(tmp_path, CHARGER % (50, 1000) + TAKER % ('near', 0.85, 1000), stageros=False)
    for _ in range(3):
        w.step()
    assert named(w, 'charger').power_pack.stored == 0.0
    assert named(w, 'near').power_pack.stored == 150.0
    w = world(tmp_path, CHARGER % (-1, 1000) + TAKER % ('near', 0.85, 1000), stageros=False)
    for _ in range(120):
        w.step()
    assert named(w, 'near').power_pack.stored == 10000.0


def test_a_static_charger_moved_at_run_time_charges_where_it_now_stands(tmp_path):
    # its cells (and the quiet chargers' look) found again after set_pose: a robot it was
    # moved beside is charged from the next update on
    w = world(tmp_path, CHARGER % (-1, 500) + TAKER % ('robot', -2, 300), stageros=False)
    charger, robot = named(w, 'charger'), named(w, 'robot')
    for _ in range(3):
        w.step()
    assert robot.power_pack.stored == 100.0 and not robot.power_pack.charging
    w.handle(charger).set_pose((-1.85, 0.0, 0.0, 0.0))     # against the robot's front
    w.step()
    assert robot.power_pack.charging
    assert robot.power_pack.stored == pytest.approx(100.0 + 300 * 0.1)


def listed_in_python(space, xs, ys, layer):
    """The moving blocks' models listed in cells (xs, ys): each cell's list walked."""
    from stage_lite.model.grid import REGION, region_index
    found = []
    for x, y in zip(xs.tolist(), ys.tolist(), strict=True):
        reg = region_index(x, y, space.rx0, space.ry0, space.nrx, space.nry)
        if reg < 0 or space.reg_dyn[reg] < 0:
            continue
        e = space.dyn_head[space.reg_dyn[reg], layer, (y % REGION) * REGION + x % REGION]
        while e >= 0:
            found.append(int(space.blk_model[space.ent_block[e]]))
            e = space.ent_next[e]
    return found


def test_a_charger_along_a_robots_edge_finds_it_in_every_shared_cell(tmp_path):
    # the robot's lower edge lies on the charger's upper one: some 190 cells list it (the
    # kernel's list grows past its first 64)
    long_charger = ('model( name "charger" pose [ 0 0 0 0 ] size [ 4 0.1 0.3 ]'
                    ' obstacle_return 0 joules -1 give_watts 500 alwayson 1 )\n')
    long_robot = ('position( name "long" pose [ 0 0.25 0 0 ] size [ 3.8 0.4 0.3 ] joules 100'
                  ' joules_capacity 10000 take_watts 300 )\n')
    w = world(tmp_path, long_charger + long_robot + TAKER % ('away', -3, 300), stageros=False)
    w.step()
    charger, robot = named(w, 'charger'), named(w, 'long')
    layer = w.updates % 2
    xs, ys = w.energy._cells_of(charger, layer)
    listed = _dynamic_models(xs, ys, layer, w.space.rx0, w.space.ry0, w.space.nrx,
                             w.space.nry, w.space.reg_dyn, w.space.dyn_head,
                             w.space.ent_block, w.space.ent_next, w.space.blk_model)
    assert sorted(listed.tolist()) == sorted(listed_in_python(w.space, xs, ys, layer))
    assert len(listed) > 64 and set(listed.tolist()) == {robot.index}
    assert w.energy.touching(charger) == [robot]
    assert robot.power_pack.stored == pytest.approx(100.0 + 300 * 0.1)
    assert named(w, 'away').power_pack.stored == 100.0


def test_a_charger_is_passed_over_only_when_it_touches_nobody(tmp_path):
    # A robot driving through a static charger, and a charger touching a static taker: each
    # step, the chargers Energy skips (_quiet_chargers) are those whose touching() is empty;
    # the one beside the static taker is never skipped, the other is both skipped and not.
    taker_wall = ('model( name "battery" pose [ -3 2.15 0 0 ] size [ 0.4 0.4 0.3 ] joules 100'
                  ' joules_capacity 10000 take_watts 100 obstacle_return 0 )\n')
    wall_charger = ('model( name "dock" pose [ -3 1.8 0 0 ] size [ 0.4 0.3 0.3 ] joules -1'
                    ' give_watts 200 obstacle_return 0 alwayson 1 )\n')
    w = world(tmp_path, CHARGER % (-1, 500) + TAKER % ('passer', -0.5, 300) + taker_wall
              + wall_charger)            # (stageros's: every robot subscribed, so it moves)
    charger, dock, passer = named(w, 'charger'), named(w, 'dock'), named(w, 'passer')
    robot = next(i for i, r in enumerate(w.robots) if r.model is passer)
    skipped, charging = [], []
    for _ in range(40):
        w.set_command(robot, 0.5, 0.0, 0.0)
        w.step()
        charging.append(passer.power_pack.charging)
        quiet = w.energy._quiet_chargers()
        for m in (charger, dock):
            assert (m in quiet) == (w.energy.touching(m) == [])
        skipped.append(charger in quiet)
        assert dock not in quiet
    assert True in skipped and False in skipped
    assert passer.power_pack.stored > 100.0
    # charged while it touched the charger, and no longer once it has driven past it (the
    # quiet charger still clears what it charged)
    assert True in charging and not charging[-1]
