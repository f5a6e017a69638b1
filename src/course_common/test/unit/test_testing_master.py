"""Unit tests of course_common.testing.master's queries on a given system state (no master)."""
import pytest
from course_common.testing.master import (
    graph_names,
    has_connection,
    names_under,
    nodes_of,
    published_topics,
    publishers_of,
    services,
    services_of,
    subscribed_topics,
    subscribers_of,
)

# getSystemState's [publishers, subscribers, services], each [name, [node, ...]].
STATE = [
    [['/chatter', ['/talker', '/talker2']], ['/rosout', ['/talker', '/listener']],
     ['/robot1/pose', ['/turtlesim']]],
    [['/chatter', ['/listener']], ['/robot1/cmd_vel', ['/turtlesim']]],
    [['/talker/get_loggers', ['/talker']], ['/spawn', ['/turtlesim']],
     ['/robot1/teleport_absolute', ['/turtlesim']]],
]


@pytest.mark.parametrize('name, column, nodes', [
    ('/chatter', 0, {'/talker', '/talker2'}),
    ('/chatter', 1, {'/listener'}),
    ('/spawn', 2, {'/turtlesim'}),
    ('/nothing', 0, set()),
])
def test_nodes_of(name, column, nodes):
    assert nodes_of(name, column, STATE) == nodes


def test_publishers_and_subscribers_of():
    assert publishers_of('/rosout', STATE) == {'/talker', '/listener'}
    assert subscribers_of('/robot1/cmd_vel', STATE) == {'/turtlesim'}
    assert subscribers_of('/rosout', STATE) == set()


def test_topic_and_service_sets():
    assert published_topics(STATE) == {'/chatter', '/rosout', '/robot1/pose'}
    assert subscribed_topics(STATE) == {'/chatter', '/robot1/cmd_vel'}
    assert services(STATE) == {'/talker/get_loggers', '/spawn', '/robot1/teleport_absolute'}
    assert services_of('/talker', STATE) == {'/talker/get_loggers'}
    topics, svcs = graph_names(STATE)
    assert topics == {'/chatter', '/rosout', '/robot1/pose', '/robot1/cmd_vel'}
    assert svcs == services(STATE)


@pytest.mark.parametrize('prefix', ['/robot1', '/robot1/'])
def test_names_under(prefix):
    assert names_under(prefix, STATE) == {'/robot1/pose', '/robot1/cmd_vel',
                                          '/robot1/teleport_absolute'}


def test_names_under_is_not_a_name_prefix():
    state = [[['/robot10/pose', ['/sim']]], [], []]
    assert names_under('/robot1', state) == set()


# getBusInfo rows: [connection id, peer, direction, transport, topic, connected, info]
BUS = [[1, '/test', 'o', 'TCPROS', '/turtle1/cmd_vel', True, ''],
       [2, '/turtlesim', 'i', 'TCPROS', '/turtle1/pose', True, '']]


@pytest.mark.parametrize('peer, topic, direction, expected', [
    ('/test', '/turtle1/cmd_vel', 'o', True),
    ('/test', '/turtle1/cmd_vel', 'i', False),
    ('/turtlesim', '/turtle1/pose', 'i', True),
    ('/other', '/turtle1/cmd_vel', 'o', False),
    ('/test', '/turtle1/pose', 'o', False),
])
def test_has_connection(peer, topic, direction, expected):
    assert has_connection(BUS, peer, topic, direction) is expected
