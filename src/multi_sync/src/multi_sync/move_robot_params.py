"""move_robot's private parameters: read once, checked, in one frozen dataclass (no rospy).

The parameter server comes in as get_param (rospy.get_param in the node, a dict's get in the
tests). How the robot drives defaults to DriveLimits' (the one place of the lesson's 0.2 m/s,
0.5 m and 1.0 m).
"""
import math
from dataclasses import dataclass

from course_common.params import check_number

from multi_sync.motion import STAGE, TURTLESIM, WORLD_SIZE_M, DriveLimits

#: On Stage, the bumper and the gap are bounded by what a laser can see, not by a square.
STAGE_MAX_DISTANCE_M = 100.0
#: The distances each simulator bounds (m): turtlesim's square (the bumper measures from the
#: robot's centre to its edge), a laser's reach on Stage.
DISTANCE_BOUNDS_M = {
    TURTLESIM: {'stop_distance_m': WORLD_SIZE_M / 2, 'min_gap_m': WORLD_SIZE_M},
    STAGE: {'stop_distance_m': STAGE_MAX_DISTANCE_M, 'min_gap_m': STAGE_MAX_DISTANCE_M},
}

# name: (lowest, highest, lowest allowed?) for each parameter; every one must be finite. The
# distances' highest is their simulator's (DISTANCE_BOUNDS_M).
_RANGES = {
    'speed_mps': (0.0, 10.0, False),
    'rate_hz': (0.0, 1000.0, False),
    'stop_distance_m': (0.0, None, True),
    'min_gap_m': (0.0, None, True),
    'cone_half_angle_rad': (0.0, math.pi, False),
    'input_timeout_s': (0.0, 3600.0, True),
    'world_size_m': (0.0, 1000.0, False),
    'announce_period_s': (0.0, 60.0, False),
    'report_period_s': (0.0, 3600.0, False),
}


@dataclass(frozen=True)
class MoveRobotConfig:
    """move_robot's private parameters (see MoveRobotNode); how it drives defaults to
    DriveLimits'."""

    speed_mps: float = DriveLimits.speed_mps
    rate_hz: float = 10.0
    stop_distance_m: float = DriveLimits.stop_distance_m
    min_gap_m: float = DriveLimits.min_gap_m
    cone_half_angle_rad: float = 0.35
    input_timeout_s: float = 2.0
    world_size_m: float = DriveLimits.world_size_m
    announce_period_s: float = 1.0
    report_period_s: float = 5.0


def load_config(get_param, simulator=None):
    """Read and check the private parameters; raise ValueError (ParamError) naming the bad one.

    get_param(name, default) reads '~name'. simulator: the robot's, TURTLESIM or STAGE, when
    it is known (move_robot_sync: STAGE; then ~world_size_m is not read, None), its bounds
    checked now (drive_limits); None for move_robot, whose first pose names it: until then
    the distances are bounded by the wider of the two simulators' bounds, Stage's, and the
    node checks them against its simulator's with drive_limits.
    """
    ranges = dict(_RANGES)
    # Not yet known: Stage's bounds, the wider.
    for name, high in DISTANCE_BOUNDS_M[simulator or STAGE].items():
        ranges[name] = (0.0, high, True)
    if simulator == STAGE:
        del ranges['world_size_m']
    values = {}
    for name, (low, high, low_ok) in ranges.items():
        values[name] = check_number('~' + name,
                                    get_param('~' + name, getattr(MoveRobotConfig, name)),
                                    low, high, low_open=not low_ok)
    if simulator == STAGE:
        values['world_size_m'] = None
    config = MoveRobotConfig(**values)
    if simulator is not None:
        drive_limits(config, simulator)
    return config


def drive_limits(config, simulator):
    """The DriveLimits the robot drives by on simulator (TURTLESIM or STAGE), from config.

    Raises ValueError (ParamError for one parameter) naming the parameters that do not fit
    that simulator: on turtlesim the bumper must stay below half its square (~world_size_m)
    and the gap within it; on Stage both within a laser's reach (STAGE_MAX_DISTANCE_M), and
    ~world_size_m plays no part.
    """
    for name, high in DISTANCE_BOUNDS_M[simulator].items():
        check_number('~' + name, getattr(config, name), 0.0, high)
    world_size_m = config.world_size_m if simulator == TURTLESIM else None
    try:
        return DriveLimits(config.speed_mps, config.stop_distance_m, config.min_gap_m,
                           world_size_m)
    except ValueError as err:
        raise ValueError('parameters ~stop_distance_m and ~world_size_m: %s' % err) from None
