"""Unit tests of rqt_graph.graph_model: the graph from the master's replies, and the filters."""
import pytest
from rqt_graph.graph_model import filter_graph, graph_from_state

# The master's replies with chat.launch running: talker -> /chatter -> listener, every node
# logging on /rosout, the rosout node republishing on /rosout_agg.
CHAT_STATE = [
    [['/chatter', ['/talker']], ['/rosout', ['/talker', '/listener']],
     ['/rosout_agg', ['/rosout']]],
    [['/chatter', ['/listener']], ['/rosout', ['/rosout']]],
    [['/talker/get_loggers', ['/talker']], ['/rosout/get_loggers', ['/rosout']]],
]
CHAT_TYPES = [['/chatter', 'std_msgs/String'], ['/rosout', 'rosgraph_msgs/Log'],
              ['/rosout_agg', 'rosgraph_msgs/Log']]


def test_chat_graph_unfiltered():
    g = graph_from_state(CHAT_STATE, CHAT_TYPES)
    assert g.nodes == {'/talker', '/listener', '/rosout'}
    assert g.topics == (('/chatter', 'std_msgs/String'), ('/rosout', 'rosgraph_msgs/Log'),
                        ('/rosout_agg', 'rosgraph_msgs/Log'))
    assert g.publishes == {('/talker', '/chatter'), ('/talker', '/rosout'),
                           ('/listener', '/rosout'), ('/rosout', '/rosout_agg')}
    assert g.subscribes == {('/chatter', '/listener'), ('/rosout', '/rosout')}


def test_default_filter_hides_rosout_and_its_edges():
    g = filter_graph(graph_from_state(CHAT_STATE, CHAT_TYPES))
    assert g.nodes == {'/talker', '/listener'}
    assert g.topic_types == {'/chatter': 'std_msgs/String'}
    assert g.publishes == {('/talker', '/chatter')}
    assert g.subscribes == {('/chatter', '/listener')}
    assert g.counts() == '2 nodes, 1 topic'


def test_show_all_keeps_everything():
    g = graph_from_state(CHAT_STATE, CHAT_TYPES)
    assert filter_graph(g, hide_debug=False) == g


@pytest.mark.parametrize('node, hidden', [
    ('/rosout', True),
    ('/rqt_gui_py_node_1234', True),   # rqt's own node
    ('/rqt_graph_2', True),
    ('/talker', False),
    ('/robot1/rqt_helper', False),     # only global /rqt_* names are viewers
    ('/rosout2', False),
])
def test_debug_nodes(node, hidden):
    state = [[['/x', [node]]], [], []]
    assert (node not in filter_graph(graph_from_state(state)).nodes) == hidden


def test_nodes_without_visible_edges_stay():
    # A node that only logs is still running: it is drawn, alone.
    state = [[['/rosout', ['/lonely']]], [], []]
    g = filter_graph(graph_from_state(state))
    assert g.nodes == {'/lonely'} and g.topics == () and not g.publishes


def test_service_only_nodes_are_nodes():
    g = graph_from_state([[], [], [['/spawn', ['/turtlesim']]]])
    assert g.nodes == {'/turtlesim'} and g.topics == ()


def test_hide_leaf_topics():
    # turtlesim with one convoy_node: cmd_vel of robot1 has no publisher, color_sensor no
    # subscriber; both are leaves. /robot2/cmd_vel and the poses connect two nodes.
    state = [
        [['/robot1/pose', ['/turtlesim']], ['/robot2/pose', ['/turtlesim']],
         ['/robot1/color_sensor', ['/turtlesim']], ['/robot2/cmd_vel', ['/convoy_node']]],
        [['/robot1/pose', ['/convoy_node']], ['/robot2/pose', ['/convoy_node']],
         ['/robot1/cmd_vel', ['/turtlesim']], ['/robot2/cmd_vel', ['/turtlesim']]],
        [],
    ]
    full = graph_from_state(state)
    assert len(filter_graph(full).topics) == 5
    g = filter_graph(full, hide_leaf_topics=True)
    assert {t for t, _ in g.topics} == {'/robot1/pose', '/robot2/pose', '/robot2/cmd_vel'}
    assert ('/robot1/cmd_vel', '/turtlesim') not in g.subscribes
    assert g.nodes == {'/turtlesim', '/convoy_node'}


def test_unknown_type_is_empty():
    g = graph_from_state([[['/a', ['/n']]], [], []], [])
    assert g.topic_types == {'/a': ''}


def test_equal_replies_give_equal_hashable_graphs():
    a = graph_from_state(CHAT_STATE, CHAT_TYPES)
    b = graph_from_state([list(reversed(col)) for col in CHAT_STATE], reversed(CHAT_TYPES))
    assert a == b and hash(a) == hash(b)


@pytest.mark.parametrize('state, words', [
    (None, 'expected [publishers, subscribers, services]'),
    ([[], []], 'expected [publishers, subscribers, services]'),
    ([[['/a']], [], []], 'malformed topic list'),
    ([[['/a', '/talker']], [], []], 'malformed topic list'),       # nodes must be a list
    ([[], [['/a', [5]]], []], "node 5 is not a global ROS name"),
    ([[['chatter', ['/talker']]], [], []], "topic 'chatter' is not a global ROS name"),
    ([[], [], [['/srv', ['talker']]]], "node 'talker' is not a global ROS name"),
    ([[], [], [[None, ['/n']]]], 'service None is not a global ROS name'),
])
def test_malformed_state_raises(state, words):
    with pytest.raises(ValueError, match=words.replace('[', r'\[').replace(']', r'\]')):
        graph_from_state(state)


@pytest.mark.parametrize('types', [[['/a']], [5], [[7, 'std_msgs/String']]])
def test_malformed_types_raise(types):
    with pytest.raises(ValueError):
        graph_from_state([[], [], []], types)
