"""Unit tests of course_common.finite: the one "finite, non-bool number" check."""
import dataclasses
import math
from dataclasses import dataclass

import pytest
from course_common.finite import check_fields, check_finite, finite_dataclass, is_finite_number


@pytest.mark.parametrize('value', [0, 0.0, -3, 2.5, 1e308, -1e-308])
def test_finite_numbers_pass(value):
    assert is_finite_number(value)
    got = check_finite('v', value)
    assert got == pytest.approx(float(value), abs=0.0)  # exact: float() only
    assert type(got) is float


@pytest.mark.parametrize('value, shown', [
    (math.nan, 'nan'), (math.inf, 'inf'), (-math.inf, '-inf'),
    (True, 'True'), (False, 'False'),              # a bool is an int, but no number here
    ('1.0', "'1.0'"), (None, 'None'), ([1.0], '[1.0]'), (1j, '1j'),
])
def test_everything_else_is_refused_by_name(value, shown):
    assert not is_finite_number(value)
    with pytest.raises(ValueError) as err:
        check_finite('speed', value)
    assert str(err.value) == 'speed = %s: expected a finite number' % shown


@pytest.mark.parametrize('value, low, low_open, expected', [
    (0.0, 0.0, False, 0.0),
    (0.5, 0.0, True, 0.5),
    (-1, -1.0, False, -1.0),
    (1e-300, 0.0, True, 1e-300),
])
def test_lower_bound_passes(value, low, low_open, expected):
    assert check_finite('v', value, low, low_open) == expected


@pytest.mark.parametrize('value, low, low_open, text', [
    (0.0, 0.0, True, 'k = 0.0: expected a finite number > 0'),
    (-0.1, 0.0, False, 'k = -0.1: expected a finite number >= 0'),
    (math.nan, 0.0, True, 'k = nan: expected a finite number > 0'),
    (math.inf, 0.0, True, 'k = inf: expected a finite number > 0'),
    (True, 0.0, True, 'k = True: expected a finite number > 0'),
    (1.0, 2.5, False, 'k = 1.0: expected a finite number >= 2.5'),
])
def test_lower_bound_refuses_by_name(value, low, low_open, text):
    with pytest.raises(ValueError) as err:
        check_finite('k', value, low, low_open)
    assert str(err.value) == text


@dataclass(frozen=True)
class _Gains:
    kp: float = 1.0
    ki: float = 0.0


@pytest.mark.parametrize('gains, low, low_open, text', [
    (_Gains(), None, False, None),
    (_Gains(), 0.0, False, None),
    (_Gains(), 0.0, True, 'ki = 0.0: expected a finite number > 0'),
    (_Gains(kp=math.nan), None, False, 'kp = nan: expected a finite number'),
    (_Gains(ki=-1), 0.0, False, 'ki = -1: expected a finite number >= 0'),
    (_Gains(kp='1'), None, False, "kp = '1': expected a finite number"),
])
def test_check_fields_names_the_first_bad_field(gains, low, low_open, text):
    if text is None:
        check_fields(gains, low, low_open)
        return
    with pytest.raises(ValueError) as err:
        check_fields(gains, low, low_open)
    assert str(err.value) == text


@pytest.mark.parametrize('obj', [_Gains, {'kp': 1.0}, None])
def test_check_fields_wants_a_dataclass_instance(obj):
    with pytest.raises(ValueError, match='expected a dataclass instance'):
        check_fields(obj)


@finite_dataclass
class _AnyFinite:
    a: float = -1.0
    b: float = 0.0


@finite_dataclass(low=0.0, low_open=True)
class _Positive:
    a: float = 1.0
    b: float = 2.0


@finite_dataclass(low=0.0)
class _Ordered:
    """Its own __post_init__ ties the fields together; it runs after the fields' check."""

    low: float = 0.0
    high: float = 1.0

    def __post_init__(self):
        if self.high < self.low:
            raise ValueError('high must be >= low')


@pytest.mark.parametrize('make, text', [
    (lambda: _AnyFinite(b=math.inf), 'b = inf: expected a finite number'),
    (lambda: _AnyFinite(a=True), 'a = True: expected a finite number'),
    (lambda: _Positive(b=0.0), 'b = 0.0: expected a finite number > 0'),
    (lambda: _Ordered(low=-1.0), 'low = -1.0: expected a finite number >= 0'),  # before its own
    (lambda: _Ordered(low=math.nan, high=0.5), 'low = nan: expected a finite number >= 0'),
    (lambda: _Ordered(low=2.0), 'high must be >= low'),
])
def test_finite_dataclass_checks_the_fields_then_its_own_rule(make, text):
    with pytest.raises(ValueError) as err:
        make()
    assert str(err.value) == text


@pytest.mark.parametrize('cls, values', [
    (_AnyFinite, (-1.0, 0.0)), (_Positive, (1.0, 2.0)), (_Ordered, (0.0, 1.0)),
])
def test_finite_dataclass_is_a_frozen_dataclass_with_its_defaults(cls, values):
    obj = cls()
    assert dataclasses.astuple(obj) == values
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(obj, dataclasses.fields(obj)[0].name, 5.0)
