"""Pins, without a master, the rospy internals course_common.rospy_internals relies on.

Each check fails naming the attribute, what it should do and the installed rospy's version.
The behaviour that needs a master and connections (a publisher's connections, frames written
to them, the /rosout cache seed, _connection_header) is pinned by rospy_internals.test.
"""
import inspect
import subprocess
import sys

import pytest
import rospy
import rospy.core
import rospy.impl.paramserver
import rospy.impl.registration
import rospy.impl.tcpros_base
import rospy.names
import rospy.topics
from course_common.testing import pin
from rospy.impl.registration import get_topic_manager

from course_common import rospy_internals

RUN_TIMEOUT_S = 60.0  # a fresh interpreter importing rospy; generous on a loaded machine


def _run(code, *argv):
    """Run code in a fresh /usr/bin/python3 (rospy's process state stays out of pytest)."""
    done = subprocess.run([sys.executable, '-c', code, *argv], capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S, check=False)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def test_param_cache_seed_is_read_back():
    cache = getattr(rospy.impl.paramserver, 'get_param_server_cache', None)
    pin(callable(cache), 'rospy.impl.paramserver.get_param_server_cache', 'exists')
    key = '/turtle_lite_unit_test_cache_key'
    cache().set(key, True)
    try:
        value = cache().get(key)
    except KeyError:
        value = None
    pin(value is True, 'ParamServerCache.set()/get()', 'returns what was set')


def test_rosout_handler_reads_the_cached_param():
    # rospy's /rosout handler must look the param up through rospy.get_param (which reads
    # the cache) under this exact name, or seeding the cache changes nothing.
    import rospy.impl.rosout as rosout
    source = inspect.getsource(rosout)
    pin('get_param_cached("%s"' % rospy_internals.ROSOUT_TOPICS_PARAM in source,
        'rospy.impl.rosout', 'reads %s through the parameter cache'
        % rospy_internals.ROSOUT_TOPICS_PARAM)


@pytest.mark.parametrize('attribute', ['add_preshutdown_hook', 'is_shutdown_requested'])
def test_shutdown_attributes_exist(attribute):
    pin(callable(getattr(rospy.core, attribute, None)), 'rospy.core.' + attribute, 'exists')


def test_signal_handler_attributes_exist():
    # shut_down_off_the_signal replaces rospy's handler only where it finds it, and chains to
    # the handler rospy recorded as the previous one.
    pin(callable(getattr(rospy.core, '_ros_signal', None)), 'rospy.core._ros_signal', 'exists')
    pin(isinstance(getattr(rospy.core, '_signalChain', None), dict), 'rospy.core._signalChain',
        'is a dict of the previous handlers')
    pin(callable(getattr(rospy.core, 'signal_shutdown', None)), 'rospy.core.signal_shutdown',
        'exists')


def test_preshutdown_hooks_get_the_reason_while_shutdown_is_requested():
    """The hook gets the reason before is_shutdown() turns true; shutdown_requested() is true
    from the hooks on (rospy closes the topics there), and was not before."""
    out = _run('import rospy\n'
               'from course_common.rospy_internals import add_preshutdown_hook, '
               'shutdown_requested\n'
               'print(shutdown_requested())\n'
               'add_preshutdown_hook(lambda r: print(r, rospy.is_shutdown(), '
               'shutdown_requested()))\n'
               'rospy.signal_shutdown("pinned_reason")\n'
               'print(shutdown_requested())\n')
    pin(out.split() == ['False', 'pinned_reason', 'False', 'True', 'True'],
        'rospy.core.add_preshutdown_hook and is_shutdown_requested',
        'call the hook with the reason before is_shutdown(), with shutdown requested '
        '(got %r)' % out)


def test_name_mappings_are_the_command_line_remaps():
    pin(callable(getattr(rospy.names, 'get_mappings', None)), 'rospy.names.get_mappings',
        'exists')
    out = _run('from course_common.rospy_internals import name_mappings\n'
               'print(sorted(name_mappings().items()))\n', 'input:=turtlesim1/turtle1',
               '/turtle1:=/robot1')
    pin(out == "[('/turtle1', '/robot1'), ('input', 'turtlesim1/turtle1')]",
        'rospy.names.get_mappings()', 'returns the unresolved argv remaps (got %r)' % out)


@pytest.mark.parametrize('method', ['remove_connection', 'add_connection'])
def test_publisher_impl_methods(method):
    pin(callable(getattr(rospy.topics._PublisherImpl, method, None)),
        'rospy.topics._PublisherImpl.%s' % method, 'exists')


@pytest.mark.parametrize('attribute', ['connections', 'closed'])
def test_topic_impl_attributes(attribute):
    impl = rospy.topics._PublisherImpl('/pinned', rospy.AnyMsg)
    pin(hasattr(impl, attribute), '_PublisherImpl.%s' % attribute, 'exists')
    pin(impl.connections == [] and impl.closed is False,
        '_PublisherImpl.connections/closed', 'start as [] and False')


@pytest.mark.parametrize('attribute', ['socket', 'endpoint_id', 'stat_bytes', 'stat_num_msg',
                                       'close'])
def test_transport_attributes(attribute):
    transport = rospy.impl.tcpros_base.TCPROSTransport(
        rospy.impl.tcpros_base.TCPROSTransportProtocol('/pinned', rospy.AnyMsg), '/pinned')
    pin(hasattr(transport, attribute), 'TCPROSTransport.%s' % attribute, 'exists')


def test_unqueued_publisher_keeps_plain_connections():
    # write_frame() writes to impl.connections, so a publisher from unqueued_publisher()
    # (rospy's public queue_size=None) must hold the transports themselves, not rospy's
    # QueuedConnection wrappers; remove_connection() takes one out again. A fresh interpreter
    # so the publisher stays out of pytest's rospy state.
    out = _run('import rospy.impl.tcpros_base as base\n'
               'from std_msgs.msg import String\n'
               'from course_common.publishers import unqueued_publisher\n'
               'pub = unqueued_publisher("/pinned", String)\n'
               'impl = pub.impl\n'
               't = base.TCPROSTransport(base.TCPROSTransportProtocol("/pinned", String), "/p")\n'
               'impl.add_connection(t)\n'
               'added = impl.connections == [t]\n'
               'impl.remove_connection(t)\n'
               'print(impl.queue_size, added, impl.connections == [])\n')
    queue_size, added, removed = out.split()
    pin(queue_size == 'None', 'Publisher(queue_size=None).impl.queue_size',
        'is None (got %s)' % queue_size)
    pin(added == 'True', '_PublisherImpl.add_connection() with queue_size None',
        'adds the transport itself to impl.connections')
    pin(removed == 'True', '_PublisherImpl.remove_connection()',
        'removes the transport from impl.connections')


def test_connection_header_is_set_on_received_messages():
    source = inspect.getsource(rospy.impl.tcpros_base)
    pin('._connection_header = ' in source, 'message._connection_header',
        'is set by rospy.impl.tcpros_base on every received message')


def test_topic_checks_are_the_registration_threads_check_all():
    manager = get_topic_manager()
    pin(callable(getattr(manager, 'check_all', None)), '_TopicManager.check_all', 'exists')
    for attribute in ('lock', 'pubs', 'subs'):
        pin(hasattr(manager, attribute), '_TopicManager.%s' % attribute, 'exists')
    pin(callable(getattr(rospy.topics._TopicImpl, 'check', None)), '_TopicImpl.check', 'exists')
    source = inspect.getsource(rospy.impl.registration.RegManager.run)
    pin('get_topic_manager().check_all()' in source, 'RegManager.run',
        'calls get_topic_manager().check_all() (looked up at each call)')


class _Impl:
    def __init__(self, connected):
        self.connections = [object()] if connected else []
        self.checked = 0

    def check(self):
        self.checked += 1


def test_throttled_topic_checks_check_connected_topics_at_most_once_a_period(monkeypatch):
    manager = get_topic_manager()
    connected, idle = _Impl(True), _Impl(False)
    monkeypatch.setattr(manager, 'pubs', {'/a': connected, '/b': idle})
    monkeypatch.setattr(manager, 'subs', {})
    monkeypatch.setattr(manager, 'check_all', manager.check_all)   # undone after the test
    rospy_internals.throttled_topic_checks(period_s=3600.0)
    manager.check_all()
    manager.check_all()          # within the period: nothing
    assert (connected.checked, idle.checked) == (1, 0)


def test_subscriber_connections_end_in_their_receive_loop():
    # one_receive_thread() replaces robust_connect_subscriber, looked up by name when rospy
    # starts a connection's thread, and takes over where it calls conn.receive_loop.
    import rospy.impl.tcpros_pubsub as pubsub
    pin(callable(getattr(pubsub, 'robust_connect_subscriber', None)),
        'rospy.impl.tcpros_pubsub.robust_connect_subscriber', 'exists')
    pin('target=robust_connect_subscriber' in inspect.getsource(pubsub.TCPROSHandler),
        'TCPROSHandler.create_transport', 'starts robust_connect_subscriber by its name')
    pin('conn.receive_loop(receive_cb)' in inspect.getsource(pubsub.robust_connect_subscriber),
        'robust_connect_subscriber', 'ends in conn.receive_loop(receive_cb)')


@pytest.mark.parametrize('attribute', ['read_buff', 'stat_bytes', 'stat_num_msg', 'header',
                                       'is_latched', 'latch', 'name', 'done', 'socket'])
def test_subscriber_transport_keeps_what_receive_once_uses(attribute):
    # the state one_receive_thread's reads update as receive_once does
    source = inspect.getsource(rospy.impl.tcpros_base.TCPROSTransport)
    pin('self.%s' % attribute in source, 'TCPROSTransport.' + attribute,
        'is the transport state receive_once reads or updates')


def test_subscriber_protocol_reads_messages_off_the_buffer():
    import rospy.impl.tcpros_pubsub as pubsub
    protocol = pubsub.TCPROSSub('/pinned', rospy.AnyMsg, queue_size=1)
    pin(callable(getattr(protocol, 'read_messages', None)) and protocol.buff_size > 0,
        'TCPROSSub.read_messages()/buff_size', 'deserialise the buffer / size a recv')


# A subscription's registration answer (no publisher yet) queued after the master's newer
# publisherUpdate naming stageros, as when stageros registers during the registration call;
# a sentinel topic queued first is connected last, once both /scan lists are dealt with.
_UPDATES_OUT_OF_ORDER = '''
import sys, threading
import rospy.impl.registration as registration
from course_common import rospy_internals

class Handler:
    done = False
    def __init__(self):
        self.lock, self.connected, self.sentinel = threading.Lock(), [], threading.Event()
    def _connect_topic(self, topic, uri):
        with self.lock:
            self.connected.append((topic, uri))
        if topic == '/sentinel':
            self.sentinel.set()
        return 1, 'connected', 0

if sys.argv[1] == 'keep':
    rospy_internals.keep_every_publisher_update()
    rospy_internals.keep_every_publisher_update()   # a second call changes nothing
handler = Handler()
manager = registration.RegManager(handler)
manager.publisher_update('/sentinel', ['http://sentinel:1/'])
manager.publisher_update('/scan', ['http://stage:2/', 'http://other:3/'])  # publisherUpdate
manager.publisher_update('/scan', ['http://other:3/'])     # registerSubscriber's answer
loop = threading.Thread(target=manager.run, daemon=True)
loop.start()
assert handler.sentinel.wait(30), 'the registration loop connected nothing'
handler.done = True
for thread in threading.enumerate():
    if thread is not threading.current_thread():
        thread.join(30)
print(sorted(uri for topic, uri in handler.connected if topic == '/scan'))
'''


def test_a_publisher_named_out_of_order_is_still_connected():
    assert _run(_UPDATES_OUT_OF_ORDER, 'keep') == "['http://other:3/', 'http://stage:2/']"


def test_plain_rospy_drops_a_publisher_named_out_of_order():
    # the race keep_every_publisher_update() closes; if rospy fixes it, this says so
    pin(_run(_UPDATES_OUT_OF_ORDER, 'plain') == "['http://other:3/']",
        'RegManager.run', 'keeps only the publisher list queued last for a topic')


# CLIENTS connections to a TCPROS server socket that accepts none yet, then every one it
# queued accepted. A connect() on loopback returns at once when the kernel queues it; once
# the queue is full the kernel drops the SYN, and the connects stop at the first that is
# still waiting after 1 s (a plain rospy server).
_QUEUED_CONNECTIONS = '''
import os, socket, sys
os.environ['ROS_HOSTNAME'] = 'localhost'
import rospy.impl.tcpros_base as tcpros_base
from course_common import rospy_internals
CLIENTS = 40
if sys.argv[1] == 'deep':
    rospy_internals.deep_tcpros_backlog()
    rospy_internals.deep_tcpros_backlog()   # a second call changes nothing
server = tcpros_base.TCPServer(lambda sock, addr: None)
clients = []
try:
    for _ in range(CLIENTS):
        clients.append(socket.create_connection(('127.0.0.1', server.port),
                                                timeout=10 if sys.argv[1] == 'deep' else 1))
except TimeoutError:
    pass
server.server_sock.setblocking(False)
queued = 0
while True:
    try:
        server.server_sock.accept()[0].close()
    except BlockingIOError:
        break
    queued += 1
print(queued)
'''


def test_the_tcpros_server_queues_many_connections_at_once():
    assert _run(_QUEUED_CONNECTIONS, 'deep') == '40'


def test_plain_rospy_queues_few_connections():
    # what deep_tcpros_backlog() changes; if rospy listens deeper one day, this says so
    queued = int(_run(_QUEUED_CONNECTIONS, 'plain'))
    pin(queued < 40, 'rospy.impl.tcpros_base.TCPServer',
        'listens with a small backlog (%d of 40 connections queued)' % queued)
