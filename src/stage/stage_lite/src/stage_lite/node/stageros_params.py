"""stageros's private parameters, read once into a frozen dataclass and checked.

A bad value is fatal (load_or_exit logs the parameter, its value and the expectation and
exits 1): a simulator silently running at the wrong speed or with other frame names would
mislead more than it helps.
"""
from dataclasses import dataclass

from course_common.param_loader import get_private
from course_common.params import ParamError, check_flag, check_number, check_text

from .pacing import check_speedup

DEFAULT_IMAGE_PATH = '~/.ros/stage_lite.png'


@dataclass(frozen=True)
class StageParams:
    """The node's settings; see stageros_node's docstring for each one's meaning."""

    base_watchdog_timeout_s: float = 0.2
    speedup: float | None = None       # None: the world's `speedup` (default 1: real time)
    tf2_frames: bool = False
    publish_stall: bool = False
    odom_child_frame: bool = False
    publish_map: bool = False
    map_resolution_m: float = 0.05
    save_image_service: bool = False
    image_path: str = DEFAULT_IMAGE_PATH
    is_depth_canonical: bool = True    # stageros's: depth 32FC1 in m, else 16UC1 in mm


def _speedup(value):
    if value is None:
        return None
    try:
        return check_speedup(value)
    except ValueError as err:
        raise ParamError('~speedup', value, '-1 (as fast as possible) or a finite number > 0') \
            from err


def load_params():
    """StageParams from the private parameters (ParamError on a bad one)."""
    return StageParams(
        # stage_ros reads a double; any finite number goes, <= 0 switches the watchdog off.
        base_watchdog_timeout_s=check_number('~base_watchdog_timeout',
                                             get_private('base_watchdog_timeout', 0.2)),
        speedup=_speedup(get_private('speedup', None)),
        tf2_frames=check_flag('~tf2_frames', get_private('tf2_frames', False)),
        publish_stall=check_flag('~publish_stall', get_private('publish_stall', False)),
        odom_child_frame=check_flag('~odom_child_frame', get_private('odom_child_frame', False)),
        publish_map=check_flag('~publish_map', get_private('publish_map', False)),
        map_resolution_m=check_number('~map_resolution', get_private('map_resolution', 0.05),
                                      low=0.0, high=10.0, low_open=True),
        save_image_service=check_flag('~save_image_service',
                                      get_private('save_image_service', False)),
        image_path=check_text('~image_path', get_private('image_path', DEFAULT_IMAGE_PATH),
                              'a non-empty path', strip=False),
        is_depth_canonical=check_flag('~is_depth_canonical',
                                      get_private('is_depth_canonical', True)))
