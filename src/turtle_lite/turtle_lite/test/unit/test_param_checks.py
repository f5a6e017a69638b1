"""Unit tests of turtle_lite.param_checks: parameter values, good and bad."""

import math

import pytest

from turtle_lite import param_checks


@pytest.mark.parametrize('value, minimum, allow, expected', [
    (62.5, 0.0, True, 62.5), (0, 0.0, True, 0.0), (3, 1.0, False, 3.0),
])
def test_number_accepts(value, minimum, allow, expected):
    assert param_checks.number('~rate_hz', value, minimum, allow) == expected


@pytest.mark.parametrize('value, minimum, allow, expected_text', [
    (-1.0, 0.0, True, '>= 0'), (0.0, 0.0, False, '> 0'), (math.nan, 0.0, True, 'finite'),
    (math.inf, 0.0, True, 'finite'), ('5', 0.0, True, 'finite'), (True, 0.0, True, 'finite'),
    (None, 0.0, True, 'finite'),
])
def test_number_rejects_naming_param_value_and_expectation(value, minimum, allow, expected_text):
    with pytest.raises(ValueError) as err:
        param_checks.number('~rate_hz', value, minimum, allow)
    assert str(err.value).startswith('parameter ~rate_hz has value %r: expected' % (value,))
    assert expected_text in str(err.value)


@pytest.mark.parametrize('value, ok', [
    (500, True), (2, True), (1, False), (100001, False), (5.0, False), (False, False),
])
def test_integer(value, ok):
    if ok:
        assert param_checks.integer('~trail_points', value, 2, 100000) == value
    else:
        with pytest.raises(ValueError, match=r'~trail_points .* an integer from 2 to 100000'):
            param_checks.integer('~trail_points', value, 2, 100000)


@pytest.mark.parametrize('value, expected', [('world', 'world'), (' map ', 'map')])
def test_name_accepts(value, expected):
    assert param_checks.name('~parent_frame', value) == expected


@pytest.mark.parametrize('value', ['', '  ', 'a b', 3, None])
def test_name_rejects(value):
    with pytest.raises(ValueError, match='~parent_frame'):
        param_checks.name('~parent_frame', value)


@pytest.mark.parametrize('value, min_length, expected', [
    ([], 0, ()), (['robot1'], 1, ('robot1',)), (('a', ' b'), 2, ('a', 'b')),
])
def test_name_list_accepts(value, min_length, expected):
    assert param_checks.name_list('~robots', value, min_length) == expected


@pytest.mark.parametrize('value, min_length', [
    ('robot1', 0), (['robot1'], 2), (['a', 'a'], 0), (['a', ''], 0), ([1, 2], 0),
    (['a b'], 0), (None, 0),
])
def test_name_list_rejects(value, min_length):
    with pytest.raises(ValueError, match='parameter ~robots has value'):
        param_checks.name_list('~robots', value, min_length)


@pytest.mark.parametrize('value, expected', [('/', '/'), ('sim', '/sim/'), ('/a/b/', '/a/b/')])
def test_namespace_accepts(value, expected):
    assert param_checks.namespace('~namespace', value) == expected


@pytest.mark.parametrize('value', [3, None, ['/']])
def test_namespace_rejects(value):
    with pytest.raises(ValueError, match='parameter ~namespace has value'):
        param_checks.namespace('~namespace', value)
