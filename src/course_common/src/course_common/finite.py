"""The workspace's one test for "a finite, non-bool number" (pure, no rospy).

Every model and parameter check asks the same question of a value: is it an int or a float
(a bool is an int in Python, but True is no speed), and is it finite (nan and inf poison
every sum they enter)? This module answers it once; check_finite adds the one bound the
models need (a lower one: > 0 for gains and speeds, >= 0 for tolerances), check_fields
applies it to every field of a model's frozen dataclass of constants, and finite_dataclass
declares such a dataclass with that check built in.
"""
import dataclasses
import math


def is_finite_number(value):
    """True if value is an int or float (bool excluded) and finite (not nan, not +-inf).

    Subclasses of float pass (numpy's float64 is one); strings, None and numpy's float32 do not.
    """
    return isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value)


def check_finite(name, value, low=None, low_open=False):
    """value as a float if is_finite_number(value) and it is >= low (> low with low_open).

    low None: no bound. Otherwise ValueError naming name, value and the expectation:
    ``speed = nan: expected a finite number``, ``k_rho = 0.0: expected a finite number > 0``.
    """
    if low is None:
        expected, in_range = 'a finite number', True
    else:
        expected = 'a finite number %s %g' % ('>' if low_open else '>=', low)
        in_range = is_finite_number(value) and (value > low if low_open else value >= low)
    if not is_finite_number(value) or not in_range:
        raise ValueError('%s = %r: expected %s' % (name, value, expected))
    return float(value)


def check_fields(obj, low=None, low_open=False):
    """check_finite on every field of the dataclass instance obj, named after the field.

    For a model's constants (finite_dataclass runs it on construction). ValueError for the
    first bad field, or if obj is not a dataclass instance.
    """
    if not dataclasses.is_dataclass(obj) or isinstance(obj, type):
        raise ValueError('%r: expected a dataclass instance' % (obj,))
    for field in dataclasses.fields(obj):
        check_finite(field.name, getattr(obj, field.name), low, low_open)


def finite_dataclass(cls=None, *, low=None, low_open=False):
    """cls as a frozen dataclass whose construction runs check_fields(self, low, low_open).

    For a model's constants (gains, tolerances, limits): ``@finite_dataclass`` or
    ``@finite_dataclass(low=0.0)``. A __post_init__ that cls defines runs after the fields'
    check, for the rules that tie fields together (k_alpha > k_rho).
    """
    def frozen_and_checked(cls):
        own_check = cls.__dict__.get('__post_init__')

        def post_init(self):
            check_fields(self, low, low_open)
            if own_check is not None:
                own_check(self)

        cls.__post_init__ = post_init
        return dataclasses.dataclass(frozen=True)(cls)

    return frozen_and_checked if cls is None else frozen_and_checked(cls)
