"""Unit tests of course_common.finite: the one "finite, non-bool number" check."""
import math

import pytest
from course_common.finite import check_finite, is_finite_number


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
