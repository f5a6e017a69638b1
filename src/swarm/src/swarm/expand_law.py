"""Stage's expand_swarm law (worlds/benchmark/expand_swarm.cc) on a LaserScan's ranges (pure).

Stage's swarmbot has 12 infrared sensors, sensor i looking along 30 i degrees; its controller
adds the readings along their headings and turns toward that sum, driving at 0.3 m/s only
while the sum points within 0.5 rad of ahead and the sensors ahead read enough (0.5 m in
front, less on the arcs beside it). Here the readings are a scan's beams: beam j looks along
mount_yaw + angle_min + j * angle_increment in the robot's frame (mount_yaw: the laser's yaw
on the robot, tf's base_link -> base_laser_link). stage_lite.swarm_world's ROS swarmbot has
one 12-beam sensor turned so that beam i is sensor i; any scan whose beams include the
headings the law checks (0, +-30, +-60, +-90 degrees) works too. Units: metres, radians,
m/s, rad/s; headings counter-clockwise from the robot's +x.
"""
import math
from dataclasses import dataclass

SPEED_MPS = 0.3
TURN_GAIN = 1.0
SAFE_DISTANCE_M = 0.5
SAFE_ANGLE_RAD = 0.5
#: (heading in degrees, the least range the beam along it must read to drive): expand_swarm's
#: sensors 0, 1, 2, 3, 9, 10, 11 and their limits, in the order the C && checks them
CLEAR_AHEAD = ((0, SAFE_DISTANCE_M), (30, SAFE_DISTANCE_M / 1.5), (60, SAFE_DISTANCE_M / 3.0),
               (90, SAFE_DISTANCE_M / 5.0), (-90, SAFE_DISTANCE_M / 5.0),
               (-60, SAFE_DISTANCE_M / 3.0), (-30, SAFE_DISTANCE_M / 1.5))
#: How far a beam's heading may be from a checked heading to stand for it, rad (float noise
#: of angle_min + j * increment in float32, as the scan carries them)
HEADING_TOLERANCE_RAD = 1e-4
#: Headings are rounded to this many decimals of a degree, then made radians as Stage's dtor
#: does (d * pi / 180): the scan's float32 angles then give the very headings of Stage's
#: sensors (30 i degrees), whose last bits decide which way a robot that sees nothing turns
HEADING_DECIMALS_DEG = 3


@dataclass(frozen=True)
class RingPlan:
    """A scan's geometry, made once: each beam's (cos, sin) and the beams the law checks."""

    count: int
    cos_sin: tuple          # ((cos a_j, sin a_j), ...) per beam, in beam order
    clear_ahead: tuple      # ((beam index, least range m), ...), in CLEAR_AHEAD's order


def _wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


def ring_plan(angle_min, angle_increment, count, mount_yaw=0.0):
    """The RingPlan of a scan of `count` beams; ValueError when the geometry is not finite or
    no beam looks along one of CLEAR_AHEAD's headings."""
    for name, value in (('angle_min', angle_min), ('angle_increment', angle_increment),
                        ('mount_yaw', mount_yaw)):
        if not math.isfinite(value):
            raise ValueError('%s must be finite, not %r' % (name, value))
    if count < 1:
        raise ValueError('a scan with %d beams has nothing to steer by' % count)
    headings = [round(math.degrees(mount_yaw + angle_min + j * angle_increment),
                      HEADING_DECIMALS_DEG) * math.pi / 180.0 for j in range(count)]
    clear = []
    for degrees, least in CLEAR_AHEAD:
        want = math.radians(degrees)
        near = [j for j, a in enumerate(headings)
                if abs(_wrap(a - want)) <= HEADING_TOLERANCE_RAD]
        if not near:
            raise ValueError('no beam looks along %d degrees (beams from %.4f rad every %.4f '
                             'rad, laser yaw %.4f rad): not the swarmbot\'s ring'
                             % (degrees, angle_min, angle_increment, mount_yaw))
        clear.append((near[0], least))
    return RingPlan(count, tuple((math.cos(a), math.sin(a)) for a in headings), tuple(clear))


def clean_ranges(ranges, range_max):
    """The ranges as the law reads them: +inf (no return, REP 117) as range_max; ValueError
    naming the first NaN or negative beam, or a count that is not the plan's."""
    out = []
    for j, r in enumerate(ranges):
        if r != r or r < 0:
            raise ValueError('beam %d reads %r' % (j, r))
        out.append(range_max if r == math.inf else r)
    return out


def command(plan, ranges):
    """(forward m/s, turn rad/s) that expand_swarm sets for these ranges (clean_ranges'),
    or None where it sets nothing (the sum lies on an axis: Stage's `dx == 0 || dy == 0`).

    The sums are added in beam order, as the C loop adds the sensors.
    """
    if len(ranges) != plan.count:
        raise ValueError('%d ranges for a scan of %d beams' % (len(ranges), plan.count))
    dx = dy = 0.0
    for r, (c, s) in zip(ranges, plan.cos_sin, strict=True):
        dx += r * c
        dy += r * s
    if dx == 0 or dy == 0:
        return None
    resultant = math.atan2(dy, dx)
    forward = 0.0
    if all(ranges[j] > least for j, least in plan.clear_ahead) \
            and abs(resultant) < SAFE_ANGLE_RAD:
        forward = SPEED_MPS
    return forward, TURN_GAIN * resultant
