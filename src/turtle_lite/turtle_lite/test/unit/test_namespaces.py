"""Unit tests of turtle_lite.namespaces: roscpp NodeHandle resolution."""

import pytest
from turtle_lite.namespaces import (
    TURTLE_RESOURCES,
    clean,
    node_namespace,
    resolve_mappings,
    turtle_namespace,
    turtle_resources,
)


@pytest.mark.parametrize('name, expected', [('//a//b/', '/a/b'), ('/', '/'), ('a/b', 'a/b')])
def test_clean(name, expected):
    assert clean(name) == expected


@pytest.mark.parametrize('node, expected', [('/turtlesim', '/'), ('/g1/sim', '/g1'),
                                            ('/a/b/c', '/a/b')])
def test_node_namespace(node, expected):
    assert node_namespace(node) == expected


@pytest.mark.parametrize('turtle, ns, node, mappings, expected', [
    ('turtle1', '/', '/turtlesim', {}, '/turtle1'),
    ('turtle1', '/', '/turtlesim', {'/turtle1': '/robot1'}, '/robot1'),
    ('turtle1', '/', '/turtlesim', {'turtle1': 'robot1'}, '/robot1'),
    ('turtle2', '/', '/turtlesim', {'turtle2': 'r2'}, '/r2'),
    ('turtle1', '/g1', '/g1/sim', {'turtle1': 'robot1'}, '/g1/robot1'),
    ('turtle1', '/g1', '/g1/sim', {}, '/g1/turtle1'),
    ('turtle1', '/ns1', '/ns1/turtlesim', {'/turtle1': '/robot1'}, '/ns1/turtle1'),
    ('/abs', '/g1', '/g1/sim', {}, '/abs'),
    ('grp/t', '/', '/turtlesim', {}, '/grp/t'),
    ('~priv', '/', '/turtlesim', {}, '/turtlesim/priv'),
    ('~priv', '/g1', '/g1/sim', {}, '/g1/sim/priv'),
    ('~priv', '/', '/turtlesim', {'~priv': '/p'}, '/p'),
])
def test_turtle_namespace(turtle, ns, node, mappings, expected):
    assert turtle_namespace(turtle, ns, node, mappings) == expected


def test_namespace_remap_moves_all_six():
    res = turtle_resources('turtle1', '/', '/turtlesim', {'/turtle1': '/robot1'})
    assert set(res) == set(TURTLE_RESOURCES)
    assert res == {r: '/robot1/' + r for r in TURTLE_RESOURCES}


def test_full_name_remap_moves_one_topic():
    res = turtle_resources('turtle1', '/', '/turtlesim', {'/turtle1/cmd_vel': '/cmd'})
    assert res['cmd_vel'] == '/cmd'
    assert res['pose'] == '/turtle1/pose'


def test_full_name_key_is_matched_after_namespace_remap():
    both = {'/turtle1': '/robot1', '/turtle1/cmd_vel': '/cmd'}
    assert turtle_resources('turtle1', '/', '/turtlesim', both)['cmd_vel'] == '/robot1/cmd_vel'
    chained = {'/turtle1': '/robot1', '/robot1/cmd_vel': '/cmd'}
    assert turtle_resources('turtle1', '/', '/turtlesim', chained)['cmd_vel'] == '/cmd'


def test_special_and_param_mappings_ignored():
    table = resolve_mappings({'__name': 'x', '__log': '/tmp/l', '_param': '3', 'a': 'b'},
                             '/', '/turtlesim')
    assert table == {'/a': '/b'}


@pytest.mark.parametrize('name', ['my turtle', '1abc', '_u', 'a-b'])
def test_invalid_names_raise(name):
    with pytest.raises(ValueError, match='Graph Resource Name'):
        turtle_resources(name, '/', '/turtlesim', {})
