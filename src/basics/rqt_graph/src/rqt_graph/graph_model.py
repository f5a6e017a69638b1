"""The ROS computation graph as rqt_graph's "Nodes/Topics (all)" view sees it (no rospy).

Built from the master's system state (getSystemState) and topic types (getTopicTypes); every
name is a global ROS name ("/talker", "/chatter"). Filtering mirrors rqt_graph's "Hide"
check boxes: the debug ones (/rosout, graph viewers) by default, leaf topics on request.
"""
from dataclasses import dataclass, replace

#: Topics rqt_graph hides as "debug": every node's log stream and its aggregate.
DEBUG_TOPICS = frozenset({'/rosout', '/rosout_agg'})
#: Nodes hidden as "debug": the log collector, and graph viewers (rqt's own nodes are
#: /rqt_gui_py_node_<pid>; a user may name one of ours /rqt_graph_*).
DEBUG_NODES = frozenset({'/rosout'})
DEBUG_NODE_PREFIXES = ('/rqt_',)


@dataclass(frozen=True)
class RosGraph:
    """Nodes, topics and who publishes or subscribes what.

    nodes: node names. topics: {topic: type} ('' when the master does not know the type).
    publishes: (node, topic) pairs. subscribes: (topic, node) pairs, in the edge's direction.
    """

    nodes: frozenset
    topics: tuple  # sorted (topic, type) pairs: hashable, so a RosGraph compares and hashes
    publishes: frozenset
    subscribes: frozenset

    @property
    def topic_types(self):
        return dict(self.topics)

    def counts(self):
        """'N nodes, M topics', for status lines."""
        return '%d node%s, %d topic%s' % (len(self.nodes), '' if len(self.nodes) == 1 else 's',
                                          len(self.topics), '' if len(self.topics) == 1 else 's')


def _check_name(name, what):
    if not isinstance(name, str) or not name.startswith('/'):
        raise ValueError('%s %r is not a global ROS name (expected a string starting with /)'
                         % (what, name))
    return name


def _pairs(rows, what):
    """[[name, [node, ...]], ...] -> [(name, node), ...], checking the shape and the names."""
    pairs = []
    try:
        for name, nodes in rows:
            if not isinstance(nodes, (list, tuple)):
                raise TypeError('%r is not a list of nodes' % (nodes,))
            pairs.extend((name, node) for node in nodes)
    except (TypeError, ValueError) as err:
        raise ValueError('malformed %s list in the system state (expected [[name, [node, ...]], '
                         '...]): %s' % (what, err)) from None
    return [(_check_name(name, what), _check_name(node, 'node')) for name, node in pairs]


def graph_from_state(system_state, topic_types=()):
    """Builds the graph from the master's replies.

    system_state: getSystemState's [publishers, subscribers, services], each a list of
    [name, [node, ...]]. topic_types: getTopicTypes's [[topic, type], ...]. Nodes that only
    provide services are nodes of the graph too; service names are not drawn (as rqt_graph).
    Raises ValueError on a malformed reply.
    """
    try:
        publishers, subscribers, services = system_state
    except (TypeError, ValueError):
        raise ValueError('malformed system state %r: expected [publishers, subscribers, '
                         'services]' % (system_state,)) from None
    published = _pairs(publishers, 'topic')
    subscribed = _pairs(subscribers, 'topic')
    served = _pairs(services, 'service')
    types = {}
    for row in topic_types:
        try:
            topic, type_name = row
        except (TypeError, ValueError):
            raise ValueError('malformed topic type entry %r: expected [topic, type]'
                             % (row,)) from None
        types[_check_name(topic, 'topic')] = str(type_name)
    topic_names = {t for t, _ in published} | {t for t, _ in subscribed}
    nodes = {n for _, n in published} | {n for _, n in subscribed} | {n for _, n in served}
    return RosGraph(nodes=frozenset(nodes),
                    topics=tuple(sorted((t, types.get(t, '')) for t in topic_names)),
                    publishes=frozenset((node, topic) for topic, node in published),
                    subscribes=frozenset(subscribed))


def is_debug_node(name):
    return name in DEBUG_NODES or name.startswith(DEBUG_NODE_PREFIXES)


def filter_graph(graph, hide_debug=True, hide_leaf_topics=False):
    """The graph with rqt_graph's "Hide" filters applied.

    hide_debug: drop /rosout (node and topic), /rosout_agg, and graph viewers (/rqt_*),
    with their edges. hide_leaf_topics: drop topics that only one side uses (published with
    no subscriber, or subscribed with no publisher), as rqt_graph's "Leaf topics".
    Nodes stay even when all their edges went (a node that only logs is still running).
    """
    nodes = {n for n in graph.nodes if not (hide_debug and is_debug_node(n))}
    topics = {t for t, _ in graph.topics if not (hide_debug and t in DEBUG_TOPICS)}
    publishes = {(n, t) for n, t in graph.publishes if n in nodes and t in topics}
    subscribes = {(t, n) for t, n in graph.subscribes if n in nodes and t in topics}
    if hide_leaf_topics:
        topics = {t for _, t in publishes} & {t for t, _ in subscribes}
        publishes = {(n, t) for n, t in publishes if t in topics}
        subscribes = {(t, n) for t, n in subscribes if t in topics}
    return replace(graph, nodes=frozenset(nodes),
                   topics=tuple((t, ty) for t, ty in graph.topics if t in topics),
                   publishes=frozenset(publishes), subscribes=frozenset(subscribes))
