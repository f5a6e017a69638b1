"""What the master says about the graph, for tests and benchmarks; a private roscore; and a
subscriber whose connection was lost (LostSubscriber).

Each query takes the master's system state (getSystemState's [publishers, subscribers,
services], each a list of [name, [node, ...]]) if the caller has one, else asks the master as
this node (rosgraph.Master(rospy.get_name())); the pure part is unit-tested without a master.
"""
import os
import threading
import xmlrpc.client
from xmlrpc.server import SimpleXMLRPCServer

import rosgraph
import rosnode
import rospy

from course_common.ports import free_port
from course_common.processes import ChildProcess
from course_common.waiting import wait_for

PUBLISHERS, SUBSCRIBERS, SERVICES = 0, 1, 2  # columns of getSystemState
START_DEADLINE_S = 30.0  # roscore (roslaunch in Python) on a loaded machine


def master(caller_id=None):
    """A rosgraph.Master client calling as caller_id (default: this node's name)."""
    return rosgraph.Master(caller_id or rospy.get_name())


def system_state(state=None):
    """state, or the master's getSystemState() when None."""
    return master().getSystemState() if state is None else state


def nodes_of(name, column, state=None):
    """The nodes listed for name (a topic or a service) in one column of the system state."""
    return {node for entry, nodes in system_state(state)[column] if entry == name
            for node in nodes}


def publishers_of(topic, state=None):
    return nodes_of(topic, PUBLISHERS, state)


def subscribers_of(topic, state=None):
    return nodes_of(topic, SUBSCRIBERS, state)


def names_in(column, state=None, node=None):
    """The topics (or services) of one column with at least one node (or with `node`)."""
    return {entry for entry, nodes in system_state(state)[column]
            if nodes and (node is None or node in nodes)}


def published_topics(state=None):
    return names_in(PUBLISHERS, state)


def subscribed_topics(state=None):
    return names_in(SUBSCRIBERS, state)


def services(state=None):
    return names_in(SERVICES, state)


def services_of(node, state=None):
    """The services node offers."""
    return names_in(SERVICES, state, node)


def graph_names(state=None):
    """(set of topics with a publisher or subscriber, set of services)."""
    state = system_state(state)
    return published_topics(state) | subscribed_topics(state), services(state)


def names_under(prefix, state=None):
    """Topics and services below prefix (a namespace such as /robot1)."""
    topics, svcs = graph_names(state)
    return {n for n in topics | svcs if n.startswith(prefix.rstrip('/') + '/')}


def topic_types():
    """{topic: type} of every published topic."""
    return dict(master().getTopicTypes())


def has_connection(bus_info, peer, topic, direction='o'):
    """True when getBusInfo's connection list has one to (or from) peer on topic.

    bus_info: [[id, peer, direction ('o' out, 'i' in), transport, topic, ...], ...].
    """
    return any(c[1] == peer and c[2] == direction and c[4] == topic for c in bus_info)


def publisher_has_connected(node, topic, subscriber=None):
    """True once node's publisher of topic lists its connection to subscriber (this node).

    rospy counts a connection on the subscriber side before the publisher side has added
    it, and a message published in between is lost; a test that counts messages waits for
    the publisher's side (its getBusInfo) first.
    """
    subscriber = subscriber or rospy.get_name()
    try:
        uri = master().lookupNode(node)
        code, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo(rospy.get_name())
    except (rosgraph.MasterError, OSError):
        return False
    return code == 1 and has_connection(info, subscriber, topic)


def kill_node(name):
    """rosnode kill: asks the node to shut down through its XML-RPC API."""
    _, failed = rosnode.kill_nodes([name])
    if failed:
        raise AssertionError('rosnode kill %s failed' % name)


class LostSubscriber:
    """A subscriber whose connection was lost: registered at the master for a topic, it
    records the master's publisherUpdate calls (its XML-RPC slave API) and connects to
    nobody. A context manager: registered on entry, unregistered and stopped on exit."""

    def __init__(self, name, topic, msg_type):
        self.name, self.topic, self.msg_type = name, topic, msg_type
        self.updates = []  # (topic, [publisher URI, ...]) per publisherUpdate, in order
        self._server = SimpleXMLRPCServer(('127.0.0.1', 0), logRequests=False, allow_none=True)
        self._server.register_function(self._publisher_update, 'publisherUpdate')
        self._server.register_function(lambda caller_id: [1, '', os.getpid()], 'getPid')
        self.uri = 'http://127.0.0.1:%d/' % self._server.server_address[1]
        self._master = rosgraph.Master(name)

    def _publisher_update(self, caller_id, topic, publishers):
        self.updates.append((topic, list(publishers)))
        return [1, '', 0]

    def told_of(self, publisher_uri):
        """True once the master has sent a publisher list for the topic naming publisher_uri."""
        return any(topic == self.topic and publisher_uri in uris for topic, uris in self.updates)

    def __enter__(self):
        threading.Thread(target=self._server.serve_forever, daemon=True).start()
        self._master.registerSubscriber(self.topic, self.msg_type, self.uri)
        return self

    def __exit__(self, *exc):
        try:
            self._master.unregisterSubscriber(self.topic, self.uri)
        finally:
            self._server.shutdown()
            self._server.server_close()


class Roscore(ChildProcess):
    """roscore on a free port, for a benchmark's private graph; a context manager.

    start() sets ROS_MASTER_URI in this process's environment (a rospy node initialised
    afterwards joins this master) and waits until the master answers.
    """

    def __init__(self, port=None, log_path=None):
        super().__init__(log_path=log_path, stop_timeout_s=20.0)
        self.port = port or free_port()
        self.uri = 'http://localhost:%d' % self.port

    def start(self, argv=None):
        os.environ['ROS_MASTER_URI'] = self.uri
        super().start(argv or ['roscore', '-p', str(self.port)])
        wait_for(rosgraph.Master('/roscore_probe', master_uri=self.uri).is_online,
                 START_DEADLINE_S, 'roscore at %s' % self.uri, 0.1, alive=self.alive)
        return self
