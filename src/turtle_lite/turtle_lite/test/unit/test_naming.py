"""Unit tests of turtle_lite.naming: roscpp's name validation, turtlesim's name counter."""

import pytest
from turtle_lite.naming import NameCounter, graph_name_error, validate_graph_name


@pytest.mark.parametrize('name', ['turtle1', '/abs', 'grp/t', '~priv', 'a_b', 'A9', 'x//y', ''])
def test_valid_names(name):
    assert graph_name_error(name) is None
    validate_graph_name(name)


@pytest.mark.parametrize('name, message', [
    ('my turtle', 'Character [ ] at element [2] is not valid in Graph Resource Name '
                  '[my turtle].  Valid characters are a-z, A-Z, 0-9, / and _.'),
    ('1abc', 'Character [1] is not valid as the first character in Graph Resource Name '
             '[1abc].  Valid characters are a-z, A-Z, / and in some cases ~.'),
    ('_u', 'Character [_] is not valid as the first character in Graph Resource Name [_u].  '
           'Valid characters are a-z, A-Z, / and in some cases ~.'),
    ('a-b', 'Character [-] at element [1] is not valid in Graph Resource Name [a-b].  '
            'Valid characters are a-z, A-Z, 0-9, / and _.'),
    ('a~b', 'Character [~] at element [1] is not valid in Graph Resource Name [a~b].  '
            'Valid characters are a-z, A-Z, 0-9, / and _.'),
    ('\u00e9t\u00e9', 'Character [\u00e9] is not valid as the first character in Graph Resource '
                      'Name [\u00e9t\u00e9].  Valid characters are a-z, A-Z, / and in some '
                      'cases ~.'),
])
def test_invalid_names_have_roscpp_messages(name, message):
    assert graph_name_error(name) == message
    with pytest.raises(ValueError) as err:
        validate_graph_name(name)
    assert str(err.value) == message


def test_counter_example_from_turtlesim():
    """turtle1 alive, spawn turtle3, then '' gives turtle2, '' gives turtle4, kill turtle2,
    '' gives turtle5 (TURTLESIM.md 1.8)."""
    counter = NameCounter()
    alive = {counter.next_name(set())}
    assert alive == {'turtle1'}
    alive.add('turtle3')
    alive.add(counter.next_name(alive))
    assert 'turtle2' in alive
    name = counter.next_name(alive)
    assert name == 'turtle4'
    alive.add(name)
    alive.discard('turtle2')
    assert counter.next_name(alive) == 'turtle5'


def test_counter_reset_starts_again():
    counter = NameCounter()
    for _ in range(5):
        counter.next_name(set())
    counter.reset()
    assert counter.next_name(set()) == 'turtle1'
    assert counter.next_name({'turtle1'}) == 'turtle2'
