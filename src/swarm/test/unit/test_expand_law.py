"""expand_law: Stage's expand_swarm law on a scan's ranges."""
import math

import pytest

from swarm import expand_law

# Stage 4.3.0's worlds/benchmark/expand_swarm.cc: VSPEED, WGAIN, SAFE_DIST, SAFE_ANGLE, and
# the sensors its clear-ahead test reads (ir[k] > SAFE_DIST / d) with their divisors
STAGE_SPEED, STAGE_GAIN, STAGE_SAFE_DIST, STAGE_SAFE_ANGLE = 0.3, 1.0, 0.5, 0.5
STAGE_CLEAR_AHEAD = ((0, STAGE_SAFE_DIST), (1, STAGE_SAFE_DIST / 1.5),
                     (2, STAGE_SAFE_DIST / 3.0), (3, STAGE_SAFE_DIST / 5.0),
                     (9, STAGE_SAFE_DIST / 5.0), (10, STAGE_SAFE_DIST / 3.0),
                     (11, STAGE_SAFE_DIST / 1.5))

# the swarm world's ring (stage_lite.swarm_world, ros=True): 12 beams over 330 degrees,
# the laser turned 165 degrees, so beam i looks along 30 i degrees
RING = dict(angle_min=math.radians(-165.0), angle_increment=math.radians(30.0), count=12,
            mount_yaw=math.radians(165.0))


def ring():
    return expand_law.ring_plan(**RING)


def stage_command(ranges):
    """What Stage's controller (expand_swarm.cc) sets for IR readings."""
    dx = dy = 0.0
    for i, r in enumerate(ranges):
        a = 30.0 * i * math.pi / 180.0     # Stage's dtor
        dx += r * math.cos(a)
        dy += r * math.sin(a)
    if dx == 0 or dy == 0:
        return None
    resultant = math.atan2(dy, dx)
    clear = all(ranges[k] > least for k, least in STAGE_CLEAR_AHEAD)
    forward = STAGE_SPEED if clear and abs(resultant) < STAGE_SAFE_ANGLE else 0.0
    return forward, STAGE_GAIN * resultant


def test_the_constants_are_stages():
    assert expand_law.SPEED_MPS == STAGE_SPEED
    assert expand_law.TURN_GAIN == STAGE_GAIN
    assert expand_law.SAFE_ANGLE_RAD == STAGE_SAFE_ANGLE
    # the same limits on the same sensors: sensor k looks along 30 k degrees
    assert [(((d // 30) % 12), least) for d, least in expand_law.CLEAR_AHEAD] \
        == list(STAGE_CLEAR_AHEAD)


def test_the_ring_checks_the_beams_of_stages_sensors():
    assert [j for j, _ in ring().clear_ahead] == [0, 1, 2, 3, 9, 10, 11]


@pytest.mark.parametrize('ranges', [
    [2.0] * 12,                                       # nothing in sight
    [0.4] + [2.0] * 11,                               # a robot just ahead
    [2.0, 2.0, 2.0, 0.3, 2.0, 2.0, 2.0, 2.0, 2.0, 1.0, 2.0, 2.0],
    [0.2 + 0.15 * i for i in range(12)],              # crowded on the left side
    [1.5, 0.25, 2.0, 2.0, 0.5, 0.7, 2.0, 2.0, 0.9, 2.0, 2.0, 0.6],
])
def test_the_command_is_stages(ranges):
    got, want = expand_law.command(ring(), ranges), stage_command(ranges)
    if want is None:
        assert got is None
    else:
        assert got == want       # the same headings, added in the same order


def test_drives_into_open_space_and_stops_when_blocked():
    open_left = [2.0 if 0 < i < 6 else 0.6 for i in range(12)]
    forward, turn = expand_law.command(ring(), open_left)
    assert turn > 0                                  # toward the open left side
    blocked = [0.3] + [2.0] * 11
    forward, turn = expand_law.command(ring(), blocked)
    assert forward == 0.0 and abs(turn) == pytest.approx(math.pi, abs=0.1)  # turns away


def test_a_scan_that_is_not_the_ring_is_refused():
    with pytest.raises(ValueError, match='no beam looks along 0 degrees'):
        expand_law.ring_plan(math.radians(-165.0), math.radians(30.0), 12, 0.0)
    with pytest.raises(ValueError, match='finite'):
        expand_law.ring_plan(float('nan'), 0.5, 12, 0.0)
    with pytest.raises(ValueError, match='nothing to steer by'):
        expand_law.ring_plan(0.0, 0.5, 0, 0.0)


def test_a_fine_scan_round_the_robot_works_too():
    # 360 beams a degree apart from -180: beams along every checked heading
    plan = expand_law.ring_plan(-math.pi, math.radians(1.0), 360)
    assert plan.count == 360
    forward, _ = expand_law.command(plan, [2.0] * 359 + [1.0])   # something behind
    assert forward == expand_law.SPEED_MPS


@pytest.mark.parametrize('ranges, error', [
    ([float('nan')] + [2.0] * 11, 'beam 0 reads nan'),
    ([2.0] * 5 + [-1.0] + [2.0] * 6, 'beam 5 reads -1.0'),
])
def test_nan_and_negative_ranges_are_refused(ranges, error):
    with pytest.raises(ValueError, match=error):
        expand_law.clean_ranges(ranges, 2.0)


def test_no_return_reads_range_max():
    assert expand_law.clean_ranges([math.inf, 1.0], 2.0) == [2.0, 1.0]


def test_a_wrong_number_of_ranges_is_refused():
    with pytest.raises(ValueError, match='11 ranges for a scan of 12 beams'):
        expand_law.command(ring(), [2.0] * 11)
