"""The swarm controller's private parameters, read once into a frozen dataclass and checked."""
import math
from dataclasses import dataclass

from course_common.param_loader import get_private
from course_common.params import check_int, check_number

#: The most robots the node drives (each takes three rospy connections)
MAX_ROBOTS = 100_000
#: stage_lite.swarm_world's ROS swarmbot: its ring of 12 beams is turned 165 degrees
RING_YAW_DEG = 165.0


@dataclass(frozen=True)
class SwarmParams:
    robots: int = 0                 # 0: as many as stageros publishes scans for
    first: int = 0                  # the first robot driven (a team of nodes splits a swarm)
    rate_hz: float = 10.0           # commands per second of sim time (stageros's step rate)
    laser_yaw_rad: float = math.radians(RING_YAW_DEG)
    discover_s: float = 1.0         # wall s the robot count must stay the same to be taken
    report_period_s: float = 10.0   # sim s between status lines
    first_scan_warn_s: float = 30.0  # wall s after the start: WARN about robots without a scan


def load_params():
    """SwarmParams from the private parameters (ParamError on a bad one)."""
    return SwarmParams(
        robots=check_int('~robots', get_private('robots', 0), low=0, high=MAX_ROBOTS),
        first=check_int('~first', get_private('first', 0), low=0, high=MAX_ROBOTS - 1),
        rate_hz=check_number('~rate_hz', get_private('rate_hz', 10.0), low=0.0, high=1000.0,
                             low_open=True),
        laser_yaw_rad=math.radians(check_number('~laser_yaw_deg',
                                                get_private('laser_yaw_deg', RING_YAW_DEG),
                                                low=-360.0, high=360.0)),
        discover_s=check_number('~discover_s', get_private('discover_s', 1.0), low=0.0,
                                high=600.0),
        report_period_s=check_number('~report_period_s', get_private('report_period_s', 10.0),
                                     low=0.0, high=1e6, low_open=True),
        first_scan_warn_s=check_number('~first_scan_warn_s',
                                       get_private('first_scan_warn_s', 30.0), low=0.0,
                                       high=1e6))
