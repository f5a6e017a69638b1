"""turtlesim_node's parameters: the frozen settings read once, and the background colour.

turtlesim ignores a parameter of the wrong type and uses its default; so does this node, with
a WARN naming the parameter, the value and the expected type (see course_common.params).
"""
import os
from dataclasses import dataclass

import rospy
from course_common.params import ParamError, check_flag, check_int, check_text

from .world import DEFAULT_BACKGROUND

DEFAULT_IMAGE_PATH = '~/.ros/turtle_lite.png'


@dataclass(frozen=True)
class SimParams:
    """The node's own settings (read once at start; the background is read on clear)."""

    gui: bool = False
    image_path: str = DEFAULT_IMAGE_PATH
    save_image_on_shutdown: bool = False


def _or_default(key, default, check):
    """check(key, value of key) or, after a WARN naming the bad value, default."""
    value = rospy.get_param(key, default)
    try:
        return check(rospy.resolve_name(key), value)
    except ParamError as err:
        rospy.logwarn('%s; using the default %r', err, default)
        return default


def _check_path(name, value):
    return check_text(name, value, 'a non-empty path', strip=False)


def load_params():
    """The private ~gui, ~image_path and ~save_image_on_shutdown (defaults for bad ones)."""
    # turtlesim always opens its window: so does this one where there is a screen (a desktop,
    # ./ws desktop); without one it runs headless, quietly, unless ~gui asks for the window.
    return SimParams(gui=_or_default('~gui', bool(os.environ.get('DISPLAY')), check_flag),
                     image_path=_or_default('~image_path', DEFAULT_IMAGE_PATH, _check_path),
                     save_image_on_shutdown=_or_default('~save_image_on_shutdown', False,
                                                        check_flag))


def ensure_background_params():
    """Write ~background_r/g/b with turtlesim's defaults where absent (its start-up)."""
    for channel, default in zip('rgb', DEFAULT_BACKGROUND, strict=True):
        key = '~background_' + channel
        if not rospy.has_param(key):
            rospy.set_param(key, default)


def read_background():
    """The background params, or the built-in defaults for missing or non-int ones."""
    # Qt keeps the low 8 bits of each channel.
    return tuple(_or_default('~background_' + channel, default, check_int) & 0xFF
                 for channel, default in zip('rgb', DEFAULT_BACKGROUND, strict=True))
