"""move_robot's private parameters: read once, checked, in one frozen dataclass (no rospy).

The parameter server comes in as get_param (rospy.get_param in the node, a dict's get in the
tests). How the robot drives defaults to DriveLimits' (the one place of the lesson's 0.2 m/s,
0.5 m and 1.0 m).
"""
import math
from dataclasses import dataclass

from course_common.params import check_number

from multi_sync.motion import STAGE, WORLD_SIZE_M, DriveLimits

#: On Stage, the bumper and the gap are bounded by what a laser can see, not by a square.
STAGE_MAX_DISTANCE_M = 100.0

# name: (lowest, highest, lowest allowed?) for each parameter; every one must be finite.
_RANGES = {
    'speed_mps': (0.0, 10.0, False),
    'rate_hz': (0.0, 1000.0, False),
    'stop_distance_m': (0.0, WORLD_SIZE_M / 2, True),
    'min_gap_m': (0.0, WORLD_SIZE_M, True),
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

    get_param(name, default) reads '~name'. simulator STAGE (the Stage lesson's
    move_robot_sync): the distances are bounded by STAGE_MAX_DISTANCE_M instead of
    turtlesim's square, and ~world_size_m is not read (None)."""
    ranges = dict(_RANGES)
    if simulator == STAGE:
        del ranges['world_size_m']
        ranges['stop_distance_m'] = (0.0, STAGE_MAX_DISTANCE_M, True)
        ranges['min_gap_m'] = (0.0, STAGE_MAX_DISTANCE_M, True)
    values = {}
    for name, (low, high, low_ok) in ranges.items():
        values[name] = check_number('~' + name,
                                    get_param('~' + name, getattr(MoveRobotConfig, name)),
                                    low, high, low_open=not low_ok)
    if simulator == STAGE:
        values['world_size_m'] = None
    config = MoveRobotConfig(**values)
    try:
        DriveLimits(config.speed_mps, config.stop_distance_m, config.min_gap_m,
                    config.world_size_m)
    except ValueError as err:
        raise ValueError('parameters ~stop_distance_m and ~world_size_m: %s' % err) from None
    return config
