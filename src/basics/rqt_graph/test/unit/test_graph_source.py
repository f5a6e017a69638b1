"""Unit tests of rqt_graph.graph_source on a fake master: the filtered graph, the errors."""
import xmlrpc.client

import pytest
from rqt_graph.graph_source import GraphSource, MasterUnreachableError

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
