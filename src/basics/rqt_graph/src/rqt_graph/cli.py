"""rqt_graph's entry point: the live ROS graph in a Tk window, or written to PNG, SVG or DOT.

Reads the master through rosgraph's master API, like `rosnode list` and `rostopic list`; it
registers no node, so it never appears in the graph it draws.
"""
import argparse
import os
import socket
import sys

import rosgraph

from .dotcode import RenderError, output_format, render
from .graph_source import GraphSource, MasterUnreachableError

CALLER_ID = '/rqt_graph'  # master calls name a caller; no node of that name is registered
DEFAULT_OUT = 'rqt_graph.png'  # where the graph goes when there is no display and no --out
#: A master that does not answer within this is reported as unreachable (a host that drops
#: packets would otherwise hang the tool for minutes).
MASTER_TIMEOUT_S = 5.0
REFRESH_S = 1.0  # the window asks the master this often; rqt_graph refreshes on demand


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='rqt_graph',
        description='Draws the running ROS graph (nodes, topics, who publishes and subscribes '
                    'what) as rqt_graph\'s Nodes/Topics (all) view. With a display it opens a '
                    'window that follows the graph; without one it writes %s and exits.'
                    % DEFAULT_OUT)
    parser.add_argument('--out', metavar='FILE',
                        help='write FILE (.png, .svg or .dot) and exit, even with a display')
    parser.add_argument('--all', action='store_true',
                        help='also show /rosout (node and topic) and graph viewers (/rqt_*)')
    parser.add_argument('--hide-leaf-topics', action='store_true',
                        help='hide topics with a publisher and no subscriber, or the reverse')
    parser.add_argument('--no-groups', action='store_true',
                        help='no box around each namespace')
    args = parser.parse_args(argv)
    if args.out is not None:
        try:
            args.format = output_format(args.out)
        except ValueError as err:
            parser.error(str(err))
    return args


def write_file(source, path, fmt):
    """Writes the graph to path; returns the graph written."""
    graph, dot = source.read()
    data = render(dot, fmt)
    with open(path, 'wb') as out:
        out.write(data)
    return graph


def main(argv=None):
    """Entry point of rqt_graph; returns only through sys.exit."""
    args = parse_args(rosgraph.myargv(sys.argv if argv is None else argv)[1:])
    socket.setdefaulttimeout(MASTER_TIMEOUT_S)
    source = GraphSource(rosgraph.Master(CALLER_ID), show_all=args.all,
                         hide_leaf_topics=args.hide_leaf_topics, groups=not args.no_groups)
    out, fmt = args.out, getattr(args, 'format', None)
    try:
        source.read()  # fail early, before any window opens, if the master is not there
        if out is None:
            from .window import WindowUnavailableError, open_root, run_window
            try:
                root = open_root()
            except WindowUnavailableError as why:
                out, fmt = DEFAULT_OUT, 'png'
                print('rqt_graph: no window (%s): writing %s instead' % (why, out))
            else:
                run_window(root, source, REFRESH_S)
                sys.exit(0)
        graph = write_file(source, out, fmt)
    except (MasterUnreachableError, RenderError) as err:
        print('rqt_graph: %s' % err, file=sys.stderr)
        sys.exit(1)
    except OSError as err:
        print('rqt_graph: cannot write %s: %s' % (out, err.strerror or err), file=sys.stderr)
        sys.exit(1)
    print('rqt_graph: wrote %s (%s)' % (os.path.abspath(out), graph.counts()))
    sys.exit(0)
