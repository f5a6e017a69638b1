"""Reading a node's parameters once, the same way in every package.

A node's load function builds its frozen parameter dataclass from get_private() and the
checks of course_common.params; main() calls load_or_exit(load, label), which logs a bad
parameter as FATAL (naming it, its value and the expectation) and exits with status 1.
"""
import sys

import rospy

from course_common.params import ParamError

#: get_private()'s default that marks a parameter without a default (it must be set).
REQUIRED = object()


def get_private(name, default=REQUIRED):
    """The private parameter ~name, default if unset; None if unset and required."""
    return rospy.get_param('~' + name, None if default is REQUIRED else default)


def load_or_exit(load, label):
    """load() (the node's params); on ParamError or ValueError, FATAL 'label: error', exit 1.

    ValueError covers the model's own checks of combined values (a path that leaves the
    world, a stop distance beyond the world), which name the parameters they combine.
    """
    try:
        return load()
    except (ParamError, ValueError) as err:
        rospy.logfatal('%s: %s', label, err)
        sys.exit(1)
