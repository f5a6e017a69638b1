"""Shared helpers of the rqt_graph rostests: run the real executable, read its DOT back.

Not a test itself. The test nodes register no ROS node (they read the master through
rosgraph), so the graph they check is exactly the one the launch file started.
"""
import os
import struct
import subprocess
import sys
import tempfile

import pydot
from course_common.testing import wait_for

RUN_DEADLINE_S = 60.0  # one `rosrun rqt_graph rqt_graph` (Python start-up, dot) under load
GRAPH_DEADLINE_S = 60.0  # the launch file's nodes all registered (the convoy spawns turtles)
GTEST_OUTPUT = '--gtest_output=xml:'
PNG_SIGNATURE = b'\x89PNG\r\n\x1a\n'


def results_dir():
    """Where a test keeps the pictures it made, for a person to look at: beside its results.

    rostest hands each test node --gtest_output=xml:<results file>; elsewhere, a temp dir.
    """
    for arg in sys.argv:
        if arg.startswith(GTEST_OUTPUT):
            path = os.path.dirname(arg[len(GTEST_OUTPUT):])
            break
    else:
        path = os.path.join(tempfile.gettempdir(), 'rqt_graph_test')
    os.makedirs(path, exist_ok=True)
    return path


def rqt_graph(*args, env=None, cwd=None):
    """Runs `rosrun rqt_graph rqt_graph ARGS` to its end: (exit code, stdout, stderr)."""
    proc = subprocess.run(['rosrun', 'rqt_graph', 'rqt_graph', *args], capture_output=True,
                          text=True, timeout=RUN_DEADLINE_S, env=env or dict(os.environ),
                          cwd=cwd, check=False)
    return proc.returncode, proc.stdout, proc.stderr


class DotGraph:
    """What a DOT file of rqt_graph shows: node ellipses, topic boxes, edges by label.

    An edge (a, b) goes from a node to a topic it publishes, or from a topic to a node that
    subscribes it: the shapes tell which, so labels alone name it (a node and a topic may
    share a name, like /rosout).
    """

    def __init__(self, text):
        (dot,) = pydot.graph_from_dot_data(text)
        labels, self.nodes, self.topics, self.others = {}, set(), set(), set()
        graphs = [dot]
        while graphs:
            graph = graphs.pop()
            graphs.extend(graph.get_subgraphs())
            for item in graph.get_nodes():
                label = (item.get('label') or '').strip('"')
                if not label:
                    continue  # the node/edge/graph defaults
                labels[item.get_name()] = label
                shape = item.get('shape')
                {'ellipse': self.nodes, 'box': self.topics}.get(shape, self.others).add(label)
        self.edges = {(labels[e.get_source()], labels[e.get_destination()])
                      for e in dot.get_edges()}

    def __repr__(self):
        return 'DotGraph(nodes=%s, topics=%s, edges=%s)' % (
            sorted(self.nodes), sorted(self.topics), sorted(self.edges))


def read_dot(path):
    with open(path) as dot_file:
        return DotGraph(dot_file.read())


def wait_graph(path, predicate, what, *args):
    """Runs rqt_graph --out path until predicate(DotGraph) holds; returns that DotGraph."""
    seen = []

    def attempt():
        code, out, err = rqt_graph('--out', path, *args)
        if code != 0:
            raise AssertionError('rqt_graph exited %d: %s%s' % (code, out, err))
        seen[:] = [read_dot(path)]
        return seen[0] if predicate(seen[0]) else None
    try:
        return wait_for(attempt, GRAPH_DEADLINE_S, what, poll_s=0.5)
    except AssertionError as err:
        raise AssertionError('%s; last graph: %r' % (err, seen[0] if seen else None)) from None


def png_size(path):
    """(width, height) of a PNG file, checking its signature and header chunk."""
    with open(path, 'rb') as png:
        head = png.read(24)
    if head[:8] != PNG_SIGNATURE or head[12:16] != b'IHDR':
        raise AssertionError('%s is not a PNG file (starts %r)' % (path, head[:16]))
    return struct.unpack('>II', head[16:24])
