"""Unit tests of rqt_graph.cli without a master: options, and GraphSource on a fake master."""
import xmlrpc.client

import pytest
from rqt_graph.cli import GraphSource, MasterUnreachableError, parse_args

STATE = [[['/chatter', ['/talker']], ['/rosout', ['/talker']]],
         [['/chatter', ['/listener']]], []]


class FakeMaster:
    master_uri = 'http://localhost:11411/'

    def __init__(self, error=None):
        self.error = error

    def getSystemState(self):  # noqa: N802 - rosgraph.Master's name
        if self.error:
            raise self.error
        return STATE

    def getTopicTypes(self):  # noqa: N802 - rosgraph.Master's name
        return [['/chatter', 'std_msgs/String']]


@pytest.mark.parametrize('argv, out, fmt, show_all', [
    ([], None, None, False),
    (['--out', 'g.png'], 'g.png', 'png', False),
    (['--out', 'g.SVG', '--all'], 'g.SVG', 'svg', True),
    (['--all', '--out=g.dot'], 'g.dot', 'dot', True),
])
def test_parse_args(argv, out, fmt, show_all):
    args = parse_args(argv)
    assert (args.out, getattr(args, 'format', None), args.all) == (out, fmt, show_all)


@pytest.mark.parametrize('argv, words', [
    (['--out', 'g.jpg'], "unknown output extension '.jpg'"),
    (['--out'], 'expected one argument'),
    (['--bogus'], 'unrecognized arguments: --bogus'),
])
def test_parse_args_errors_exit_2(argv, words, capsys):
    with pytest.raises(SystemExit) as exc:
        parse_args(argv)
    assert exc.value.code == 2
    assert words in capsys.readouterr().err


def test_source_filters_and_groups():
    graph, dot = GraphSource(FakeMaster()).read()
    assert graph.nodes == {'/talker', '/listener'}
    assert graph.topic_types == {'/chatter': 'std_msgs/String'}
    assert '"n/talker" -> "t/chatter"' in dot.to_string()
    graph, _ = GraphSource(FakeMaster(), show_all=True).read()
    assert '/rosout' in graph.topic_types


@pytest.mark.parametrize('error', [
    ConnectionRefusedError(111, 'Connection refused'),
    TimeoutError('timed out'),
    xmlrpc.client.ProtocolError('localhost:11411', 404, 'Not Found', {}),
])
def test_source_unreachable_names_the_uri(error):
    with pytest.raises(MasterUnreachableError, match='http://localhost:11411/ .ROS_MASTER_URI.'):
        GraphSource(FakeMaster(error)).read()
