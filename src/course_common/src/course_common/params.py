"""Checks for node parameters, shared by every package's loader: type, range, finiteness.

Pure (no rospy): each check takes the parameter's name and value and returns the value in
its canonical type, or raises ParamError whose message names the parameter, the value and
what was expected: ``parameter ~speed_mps = -0.2: expected a finite number in (0, 10]``.
The nodes read their parameters once through param_loader.load_or_exit, which logs that
message as FATAL and exits non-zero.
"""
import math

from course_common.graph_names import normalize_namespace


class ParamError(ValueError):
    """A parameter is missing or invalid; the message names it, its value and the expectation."""

    def __init__(self, name, value, expected, missing=False):
        shown = 'is missing' if missing else '= %r' % (value,)
        super().__init__('parameter %s %s: expected %s' % (name, shown, expected))
        self.name = name
        self.value = value
        self.expected = expected


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _range_text(low, high, low_open, high_open):
    if low is not None and high is not None:
        return ' in %s%g, %g%s' % ('(' if low_open else '[', low, high, ')' if high_open else ']')
    if low is not None:
        return ' %s %g' % ('>' if low_open else '>=', low)
    if high is not None:
        return ' %s %g' % ('<' if high_open else '<=', high)
    return ''


def _in_range(value, low, high, low_open, high_open):
    if low is not None and (value <= low if low_open else value < low):
        return False
    return high is None or (value < high if high_open else value <= high)


def check_number(name, value, low=None, high=None, low_open=False, high_open=False):
    """value as a float if it is a finite int or float within the bounds (booleans are not).

    low/high are inclusive unless low_open/high_open; None means unbounded on that side.
    """
    expected = 'a finite number' + _range_text(low, high, low_open, high_open)
    if not _is_number(value) or not math.isfinite(value) \
            or not _in_range(value, low, high, low_open, high_open):
        raise ParamError(name, value, expected)
    return float(value)


def check_int(name, value, low=None, high=None):
    """value if it is an int (not a bool) in [low, high] (None: unbounded)."""
    expected = 'an integer' + _range_text(low, high, False, False)
    if not isinstance(value, int) or isinstance(value, bool) \
            or not _in_range(value, low, high, False, False):
        raise ParamError(name, value, expected)
    return value


def check_flag(name, value):
    """value if it is a bool."""
    if not isinstance(value, bool):
        raise ParamError(name, value, 'a bool (true or false)')
    return value


def check_text(name, value, what='a non-empty string', strip=True):
    """value if it is a non-empty string (None: missing).

    With strip (the default), surrounding blanks are removed and a blank string is refused.
    """
    if value is None:
        raise ParamError(name, value, what, missing=True)
    if not isinstance(value, str) or not (value.strip() if strip else value):
        raise ParamError(name, value, what)
    return value.strip() if strip else value


def _is_name(value):
    return isinstance(value, str) and bool(value.strip()) and ' ' not in value.strip()


def check_name(name, value):
    """value stripped, if it is a non-empty name without spaces (a frame or graph name)."""
    if not _is_name(value):
        raise ParamError(name, value, 'a non-empty name without spaces, e.g. world')
    return value.strip()


def check_name_list(name, value, min_length=0):
    """value as a tuple of stripped names, if it is a list of at least min_length distinct ones."""
    if not isinstance(value, (list, tuple)) or len(value) < min_length \
            or not all(_is_name(v) for v in value) or len({v.strip() for v in value}) != len(value):
        raise ParamError(name, value, 'a list of %sdistinct names, e.g. [robot1, robot2]'
                         % ('%d or more ' % min_length if min_length else ''))
    return tuple(v.strip() for v in value)


def check_namespace(name, value):
    """value as an absolute namespace ending in '/' (/, /sim or sim/ become /, /sim/)."""
    try:
        return normalize_namespace(value)
    except ValueError:
        raise ParamError(name, value, 'a namespace such as / or /turtlesim1') from None
