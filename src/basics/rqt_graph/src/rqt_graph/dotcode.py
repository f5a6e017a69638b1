"""A RosGraph as graphviz DOT (through pydot), and its rendering to PNG or SVG (no rospy).

The picture follows rqt_graph's: left to right, nodes as ellipses, topics as boxes, an edge
from each publisher to its topic and from the topic to each subscriber, and a box around each
namespace ("Group: Namespaces"). graphviz's dot lays it out.
"""
import os

import pydot

#: What --out accepts, by file extension. 'dot' is the DOT source, before layout.
FORMATS = {'.png': 'png', '.svg': 'svg', '.dot': 'dot'}
FONT = 'DejaVu Sans'  # Debian's default sans font: graphviz's Times looks dated next to Tk
#: DOT ids carry the kind so a node and a topic may share a ROS name ("/chatter" can be both).
NODE_ID = 'n%s'
TOPIC_ID = 't%s'


class RenderError(RuntimeError):
    """graphviz could not render the graph (not installed, or it failed)."""


def output_format(path):
    """'png', 'svg' or 'dot' from path's extension; ValueError for any other."""
    ext = os.path.splitext(path)[1].lower()
    if ext not in FORMATS:
        raise ValueError('unknown output extension %r in %s: expected one of %s'
                         % (ext, path, ', '.join(sorted(FORMATS))))
    return FORMATS[ext]


def namespace(name):
    """'/robot1/pose' -> '/robot1'; '/talker' -> '' (the global namespace gets no box)."""
    parts = name.strip('/').split('/')
    return '/' + parts[0] if len(parts) > 1 else ''


def build_dot(graph, clusters=True, rankdir='LR'):
    """The pydot.Dot of graph, deterministic (sorted) so equal graphs give equal DOT."""
    dot = pydot.Dot('rosgraph', graph_type='digraph', rankdir=rankdir, fontname=FONT,
                    fontsize='11', nodesep='0.3', ranksep='0.6')
    dot.set_node_defaults(fontname=FONT, fontsize='11', margin='0.15,0.06')
    dot.set_edge_defaults(color='#555555', arrowsize='0.7')
    if not graph.nodes and not graph.topics:
        dot.set('label', 'no nodes (is only the master running?)')
    parents = {}

    def parent(name):
        ns = namespace(name) if clusters else ''
        if not ns:
            return dot
        if ns not in parents:
            cluster = pydot.Cluster(ns.strip('/'), label=ns, fontname=FONT, fontsize='11',
                                    style='rounded', color='#999999')
            parents[ns] = cluster
            dot.add_subgraph(cluster)
        return parents[ns]

    for node in sorted(graph.nodes):
        parent(node).add_node(pydot.Node(NODE_ID % node, label=node, shape='ellipse',
                                         tooltip='node ' + node))
    for topic, type_name in graph.topics:  # already sorted
        parent(topic).add_node(pydot.Node(TOPIC_ID % topic, label=topic, shape='box',
                                          tooltip=type_name or 'topic ' + topic))
    for node, topic in sorted(graph.publishes):
        dot.add_edge(pydot.Edge(NODE_ID % node, TOPIC_ID % topic))
    for topic, node in sorted(graph.subscribes):
        dot.add_edge(pydot.Edge(TOPIC_ID % topic, NODE_ID % node))
    return dot


def render(dot, fmt):
    """The bytes of the file for fmt: the DOT source, or dot's PNG/SVG. Raises RenderError."""
    if fmt == 'dot':
        return dot.to_string().encode()
    if fmt not in FORMATS.values():
        raise ValueError('unknown format %r: expected one of %s'
                         % (fmt, ', '.join(sorted(FORMATS.values()))))
    try:
        return dot.create(prog='dot', format=fmt)
    except OSError as err:  # pydot reports a missing program as OSError "... not found in path"
        raise RenderError('cannot run graphviz\'s dot (%s): install the Debian package '
                          'graphviz' % err) from None
    except AssertionError as err:  # pydot asserts on a non-zero exit of dot
        raise RenderError('graphviz\'s dot failed: %s' % err) from None
