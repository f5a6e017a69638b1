"""Validation of node parameters as read from the parameter server (no rospy).

Each check takes the parameter's name (as the user writes it, e.g. ``~rate_hz``) and its value,
returns the value in the expected Python type, and raises ValueError naming the parameter, the
value and what was expected: the message of the node's logfatal.
"""

import math

from turtle_lite.team_frames import normalize_namespace


def _fail(name, value, expected):
    raise ValueError('parameter %s has value %r: expected %s' % (name, value, expected))


def number(name, value, minimum, allow_minimum=True):
    """A finite int or float >= minimum (> minimum when not allow_minimum), as float."""
    ok = (isinstance(value, (int, float)) and not isinstance(value, bool)
          and math.isfinite(value) and (value >= minimum if allow_minimum else value > minimum))
    if not ok:
        _fail(name, value, 'a finite number %s %g' % ('>=' if allow_minimum else '>', minimum))
    return float(value)


def integer(name, value, minimum, maximum):
    """An int in [minimum, maximum]."""
    if not isinstance(value, int) or isinstance(value, bool) or not minimum <= value <= maximum:
        _fail(name, value, 'an integer from %d to %d' % (minimum, maximum))
    return value


def name(name, value):
    """A non-empty string without spaces (a frame or graph name), stripped."""
    if not isinstance(value, str) or not value.strip() or ' ' in value.strip():
        _fail(name, value, 'a non-empty name without spaces, e.g. world')
    return value.strip()


def name_list(name, value, min_length=0):
    """A list of distinct non-empty names, at least min_length of them, as a tuple."""
    if not isinstance(value, (list, tuple)) or len(value) < min_length \
            or not all(isinstance(v, str) and v.strip() and ' ' not in v.strip() for v in value) \
            or len({v.strip() for v in value}) != len(value):
        _fail(name, value, 'a list of %sdistinct names, e.g. [robot1, robot2]'
              % ('%d or more ' % min_length if min_length else ''))
    return tuple(v.strip() for v in value)


def namespace(name, value):
    """A namespace such as /, /sim or sim/, as an absolute namespace ending in '/'."""
    try:
        return normalize_namespace(value)
    except ValueError:
        _fail(name, value, 'a namespace such as / or /turtlesim1')
