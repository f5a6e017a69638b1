"""The graph rqt_graph draws: the master's state, filtered, as a RosGraph and its DOT.

Both the file writer (cli) and the window's worker thread (window) read the graph through
GraphSource, so neither imports the other.
"""
import xmlrpc.client

import rosgraph

from .dotcode import build_dot
from .graph_model import filter_graph, graph_from_state


class MasterUnreachableError(RuntimeError):
    """The master did not answer."""


class GraphSource:
    """The current graph from the master, filtered, as a RosGraph and its pydot.Dot."""

    def __init__(self, master, show_all=False, hide_leaf_topics=False, groups=True):
        self._master = master
        self._show_all = show_all
        self._hide_leaf_topics = hide_leaf_topics
        self._groups = groups

    def read(self):
        """(graph, dot); raises MasterUnreachableError."""
        try:
            state = self._master.getSystemState()
            types = self._master.getTopicTypes()
        except (OSError, xmlrpc.client.Error, rosgraph.MasterException) as err:
            raise MasterUnreachableError('cannot reach the ROS master at %s (ROS_MASTER_URI): %s'
                                         % (self._master.master_uri, err)) from None
        graph = filter_graph(graph_from_state(state, types), hide_debug=not self._show_all,
                             hide_leaf_topics=self._hide_leaf_topics)
        return graph, build_dot(graph, clusters=self._groups)
