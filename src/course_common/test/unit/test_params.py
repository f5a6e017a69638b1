"""Unit tests for the parameter checks every package's loader uses (course_common.params)."""
import math

import pytest
from course_common.params import (
    ParamError,
    check_flag,
    check_int,
    check_name,
    check_name_list,
    check_namespace,
    check_number,
    check_text,
)


@pytest.mark.parametrize('value, bounds, expected', [
    (0.2, {}, 0.2),
    (3, {}, 3.0),
    (-1e9, {}, -1e9),
    (0.0, {'low': 0.0}, 0.0),
    (10.0, {'low': 0.0, 'high': 10.0, 'low_open': True}, 10.0),
    (5, {'high': 5}, 5.0),
])
def test_check_number_accepts(value, bounds, expected):
    got = check_number('~p', value, **bounds)
    assert got == expected
    assert isinstance(got, float)


@pytest.mark.parametrize('value, bounds, expected_text', [
    ('fast', {}, "parameter ~p = 'fast': expected a finite number"),
    (True, {}, 'parameter ~p = True: expected a finite number'),
    (None, {}, 'parameter ~p = None: expected a finite number'),
    (math.nan, {}, 'parameter ~p = nan: expected a finite number'),
    (math.inf, {'low': 0.0}, 'parameter ~p = inf: expected a finite number >= 0'),
    (-0.2, {'low': 0.0, 'high': 10.0, 'low_open': True},
     'parameter ~p = -0.2: expected a finite number in (0, 10]'),
    (0.0, {'low': 0.0, 'low_open': True}, 'parameter ~p = 0.0: expected a finite number > 0'),
    (3600, {'low': 0.0, 'high': 3600.0, 'low_open': True, 'high_open': True},
     'parameter ~p = 3600: expected a finite number in (0, 3600)'),
    (6, {'high': 5}, 'parameter ~p = 6: expected a finite number <= 5'),
    (5, {'high': 5, 'high_open': True}, 'parameter ~p = 5: expected a finite number < 5'),
])
def test_check_number_refuses_naming_parameter_value_and_expectation(value, bounds,
                                                                     expected_text):
    with pytest.raises(ParamError) as err:
        check_number('~p', value, **bounds)
    assert str(err.value) == expected_text
    assert err.value.name == '~p'
    assert isinstance(err.value, ValueError)  # callers that catch ValueError still work


@pytest.mark.parametrize('value, low, high, ok', [
    (4, 1, 20, True), (1, 1, 20, True), (20, 1, 20, True), (0, 1, 20, False),
    (21, 1, 20, False), (4.0, 1, 20, False), (True, None, None, False), ('4', None, None, False),
    (-7, None, None, True),
])
def test_check_int(value, low, high, ok):
    if ok:
        assert check_int('~n', value, low, high) == value
    else:
        with pytest.raises(ParamError, match=r'parameter ~n = .*: expected an integer'):
            check_int('~n', value, low, high)


def test_check_int_states_the_range():
    with pytest.raises(ParamError, match=r'expected an integer in \[0, 4\]$'):
        check_int('~first_id', 5, 0, 4)


@pytest.mark.parametrize('value, ok', [(True, True), (False, True), (1, False), ('true', False),
                                       (None, False)])
def test_check_flag(value, ok):
    if ok:
        assert check_flag('~gui', value) is value
    else:
        with pytest.raises(ParamError, match='expected a bool'):
            check_flag('~gui', value)


@pytest.mark.parametrize('value, strip, expected', [
    ('/robot2/pose', True, '/robot2/pose'),
    ('  /robot2/pose ', True, '/robot2/pose'),
    ('  a path ', False, '  a path '),
    ('   ', False, '   '),
])
def test_check_text_accepts(value, strip, expected):
    assert check_text('~t', value, strip=strip) == expected


@pytest.mark.parametrize('value, strip, expected_text', [
    (None, True, 'parameter ~t is missing: expected a topic'),
    ('', True, "parameter ~t = '': expected a topic"),
    ('  ', True, "parameter ~t = '  ': expected a topic"),
    ('', False, "parameter ~t = '': expected a topic"),
    (5, True, 'parameter ~t = 5: expected a topic'),
])
def test_check_text_refuses(value, strip, expected_text):
    with pytest.raises(ParamError) as err:
        check_text('~t', value, 'a topic', strip=strip)
    assert str(err.value) == expected_text


@pytest.mark.parametrize('value, expected', [('world', 'world'), (' map ', 'map')])
def test_check_name_accepts(value, expected):
    assert check_name('~parent_frame', value) == expected


@pytest.mark.parametrize('value', ['', '  ', 'a b', 3, None])
def test_check_name_rejects(value):
    with pytest.raises(ParamError, match=r'~parent_frame = .*: expected a non-empty'):
        check_name('~parent_frame', value)


@pytest.mark.parametrize('value, min_length, expected', [
    ([], 0, ()), (['robot1'], 1, ('robot1',)), (('a', ' b'), 2, ('a', 'b')),
])
def test_check_name_list_accepts(value, min_length, expected):
    assert check_name_list('~robots', value, min_length) == expected


@pytest.mark.parametrize('value, min_length', [
    ('robot1', 0), (['robot1'], 2), (['a', 'a'], 0), (['a', ''], 0), ([1, 2], 0),
    (['a b'], 0), (None, 0),
])
def test_check_name_list_rejects(value, min_length):
    with pytest.raises(ParamError, match=r'parameter ~robots = .*: expected a list of'):
        check_name_list('~robots', value, min_length)


@pytest.mark.parametrize('value, expected', [('/', '/'), ('sim', '/sim/'), ('/a/b/', '/a/b/')])
def test_check_namespace_accepts(value, expected):
    assert check_namespace('~namespace', value) == expected


@pytest.mark.parametrize('value', [3, None, ['/']])
def test_check_namespace_rejects(value):
    with pytest.raises(ParamError, match=r'parameter ~namespace = .*: expected a namespace'):
        check_namespace('~namespace', value)
