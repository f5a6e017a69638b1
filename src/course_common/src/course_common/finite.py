"""The workspace's one test for "a finite, non-bool number" (pure, no rospy).

Every model and parameter check asks the same question of a value: is it an int or a float
(a bool is an int in Python, but True is no speed), and is it finite (nan and inf poison
every sum they enter)? This module answers it once; the callers add their own ranges.
"""
import math


def is_finite_number(value):
    """True if value is an int or float (bool excluded) and finite (not nan, not +-inf).

    Subclasses of float pass (numpy's float64 is one); strings, None and numpy's float32 do not.
    """
    return isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value)


def check_finite(name, value):
    """value as a float if is_finite_number(value); ValueError naming name and value otherwise.

    The message reads ``speed = nan: expected a finite number``.
    """
    if not is_finite_number(value):
        raise ValueError('%s = %r: expected a finite number' % (name, value))
    return float(value)
