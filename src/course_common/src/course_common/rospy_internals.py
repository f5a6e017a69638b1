"""The one place in the workspace that reaches past rospy's public API.

turtle_lite's simulator and tools and multi_sync's monitor import these shortcuts from here
(every package depends on course_common); no other module touches ``Publisher.impl``,
``rospy.impl``, ``rospy.core``, ``rospy.names`` or a message's ``_connection_header``.

Each shortcut is a small function saying which public call it replaces and what that saves.
test/unit/test_rospy_internals.py (no master) and test/rospy_internals.test (a master and
a real subscriber) pin every attribute used here against the installed rospy: if a ros_comm
update renames or changes one, those tests fail naming it, instead of the simulator becoming
slow or silent.
"""
import atexit
import contextlib
import functools
import itertools
import signal
import socket
import threading
import time
import traceback

import rospy
import rospy.core
import rospy.impl.registration
import rospy.impl.tcpros_base
import rospy.impl.tcpros_pubsub
import rospy.names
from genpy import DeserializationError
from rospy.impl.paramserver import get_param_server_cache
from rospy.impl.registration import get_topic_manager

from course_common.receive_thread import ReceiveThread
from course_common.tcpros_frames import FrameStream, split_frames

#: The parameter whose local cache entry cheap_rosout() and cache_rosout_param() seed.
ROSOUT_TOPICS_PARAM = '/rosout_disable_topics_generation'
#: The attribute of a connection (rospy's transport) holding write_frame's FrameStream.
STREAM_ATTR = 'course_frame_stream'
#: How long the interpreter's exit waits for a signal's shutdown (shut_down_off_the_signal), s
SIGNAL_SHUTDOWN_WAIT_S = 10.0
#: throttled_topic_checks(): at most one check of every topic's connections this often, s
#: (rospy's own period when no registration comes in: RegManager.run's cond.wait(0.5))
TOPIC_CHECK_PERIOD_S = 0.5
#: deep_tcpros_backlog(): connections the TCPROS server's socket queues before it accepts
#: them (rospy's is 5; the kernel holds it to net.core.somaxconn)
TCPROS_BACKLOG = socket.SOMAXCONN


def has_subscribers(pub):
    """True if ``pub`` has at least one connected subscriber.

    Replaces ``pub.get_num_connections() > 0``, which takes the impl's lock and builds a
    list; the tick asks this twice per turtle 62.5 times a second.
    """
    return bool(pub.impl.connections)


def connection_ids(pub):
    """Caller ids of the nodes connected to ``pub`` (one per subscriber connection).

    rospy has no public call for this: each transport carries the subscriber's caller id
    (``endpoint_id``) from its TCPROS connection header. multi_sync's monitor sends GO once
    every ready robot listens. Read once per status message: nothing to measure.
    """
    return {getattr(c, 'endpoint_id', '') for c in list(pub.impl.connections)}


def write_frame(pub, frame):
    """Send one ready-made TCPROS frame to every subscriber of ``pub``; never blocks.

    ``pub`` comes from course_common.publishers.unqueued_publisher (rospy's public
    ``queue_size=None``), whose connections are the transports themselves, not rospy's
    QueuedConnection wrappers: the pins check that the installed rospy still does that.

    Replaces ``pub.publish(msg)``: what rospy's _PublisherImpl.publish does after
    serialising, without the per-call checks, buffer juggling and message object. The tick
    sends up to 62.5 x 2 x N messages a second and that overhead was most of the node's CPU.
    Unlike rospy's blocking sendall, a subscriber that stops reading only loses whole frames
    (as with roscpp's queue of 1) and never stalls the tick; a frame its buffers took part of
    is finished first (course_common.tcpros_frames.FrameStream), so it keeps its connection
    and gets whole messages again once it reads. A connection that fails is removed and
    closed.
    """
    write_frames(((pub, frame),))


def write_frames(pub_frames):
    """write_frame(pub, frame) for each (pub, frame), in order: a step's frames in one call
    (stageros sends a few per robot every step)."""
    for pub, frame in pub_frames:
        impl = pub.impl
        if impl is None or impl.closed:
            continue    # unregistered (killed) between the step and the publish
        for conn in impl.connections:
            try:
                stream = conn.__dict__.get(STREAM_ATTR)
                if stream is None:
                    stream = conn.__dict__[STREAM_ATTR] = FrameStream()
                if stream.send(conn.socket, frame):
                    conn.stat_bytes += len(frame)
                    conn.stat_num_msg += 1
            except Exception:
                with contextlib.suppress(Exception):
                    impl.remove_connection(conn)
                    conn.close()


def pending_bytes(conn):
    """Bytes of a frame the connection's buffers took part of, still to be sent."""
    stream = conn.__dict__.get(STREAM_ATTR)
    return 0 if stream is None else stream.pending


def throttled_topic_checks(period_s=TOPIC_CHECK_PERIOD_S):
    """Check the node's connections for errors at most every period_s, and only topics that
    have connections. Call it before making the node's topics.

    Replaces nothing public (rospy has no switch for it): rospy's registration thread
    (RegManager.run) calls the topic manager's check_all() every 0.5 s and after every
    registration update: each subscription the node registers and each publisherUpdate the
    master sends. check_all() polls every topic's connections (an epoll syscall per topic,
    with or without connections) while holding the topic manager's lock, which registering a
    topic needs too. A node with thousands of topics thus pays O(topics) per registration:
    stageros with 1,000 swarmbots (4,004 topics) spent 13.8 s of CPU in 1,030 check_all()
    calls and its main thread 9.5 s waiting for that lock, of 23 s registering. Connections
    that break are still found and removed, within period_s as rospy does between updates;
    a topic without connections has nothing to find.
    """
    manager = get_topic_manager()
    last = [-period_s]

    def check_all():
        now = time.monotonic()
        if now - last[0] < period_s:
            return
        last[0] = now
        with manager.lock:
            for impl in itertools.chain(list(manager.pubs.values()),
                                        list(manager.subs.values())):
                if impl.connections:
                    impl.check()

    manager.check_all = check_all


def one_receive_thread():
    """Read every subscribed connection of this node in one thread. Call it before the
    node's first subscription; once per process (later calls do nothing).

    Replaces nothing public (rospy has no switch for it): rospy starts a thread per
    subscribed connection that blocks in recv() and runs the callbacks (TCPROSHandler's
    create_transport runs robust_connect_subscriber, which connects, then stays in the
    transport's receive_loop). swarm_controller at 1,000 robots subscribes 2,000 topics:
    2,000 threads woken ten times a simulated second each, taking the GIL in turn, and the
    node never received every first scan. Here rospy still connects each subscription in its
    own thread (its retries unchanged), and then, instead of its receive loop, hands the
    socket to one ReceiveThread: the same reads into the connection's buffer, the same
    deserialisation (the protocol's read_messages, with the subscription's queue_size), the
    same statistics, _connection_header and latch, then the subscription's receive_callback,
    so a callback gets the same messages in the same order per connection; callbacks of
    different connections no longer run at the same time. A connection that ends or fails
    (the publisher gone, a reset, a message that does not deserialise) goes back to rospy's
    own receive loop in a thread of its own, which meets the same end and closes or
    reconnects as rospy always does.
    """
    connect = rospy.impl.tcpros_pubsub.robust_connect_subscriber
    if getattr(connect, 'one_receive_thread', False):
        return
    receiver = ReceiveThread('tcpros_receive', _receive_error)

    def connect_then_share(conn, *args):
        conn.receive_loop = functools.partial(_share_connection, receiver, conn)
        connect(conn, *args)

    connect_then_share.one_receive_thread = True
    rospy.impl.tcpros_pubsub.robust_connect_subscriber = connect_then_share


def _receive_error(reader, error):
    rospy.core.rospyerr('one_receive_thread: %s dropped: %s', reader, error)


def _share_connection(receiver, conn, receive_cb):
    """What conn.receive_loop(receive_cb) does, in the receiver: its socket added to it."""
    del conn.receive_loop                   # the class's own again, for a hand-back
    close = conn.close

    def forget_then_close():
        if conn.socket is not None:
            receiver.remove(conn.socket)
        close()

    conn.close = forget_then_close
    conn.socket.setblocking(False)
    # The handshake's read may have taken messages (a latched one): delivered first, in the
    # receiving thread too, so that no two callbacks of the node's connections overlap.
    receiver.add(conn.socket, functools.partial(_read_connection, conn, receive_cb),
                 first=functools.partial(_deliver_or_hand_back, conn, receive_cb))
    return None


def _read_connection(conn, receive_cb):
    """One readable event: receive_once's read and what follows it. True to stay."""
    if conn.done or rospy.core.is_shutdown():
        return False
    try:
        data = conn.socket.recv(conn.protocol.buff_size)
    except BlockingIOError:
        return True
    except OSError:
        data = b''
    if not data:                # ended or failed: rospy's loop meets it again and acts
        _hand_back(conn, receive_cb)
        return False
    conn.stat_bytes += len(data)
    conn.read_buff.write(data)
    return _deliver_or_hand_back(conn, receive_cb)


def _deliver_or_hand_back(conn, receive_cb):
    """The buffer's whole messages delivered: True; or the connection handed back: False."""
    if _deliver(conn, receive_cb):
        return True
    _hand_back(conn, receive_cb)
    return False


def deliver_bodies(sub, handler):
    """With one_receive_thread(): sub's messages go to ``handler(bodies, conn)`` as their
    serialised bodies (bytes, oldest first; of those read at once, the last queue_size, as
    rospy keeps) instead of being deserialised for the topic's callbacks.

    For a message of fixed layout (a Twist is 6 float64) a struct.unpack is a fraction of
    rospy's message objects and callback loop: stageros on a swarm receives a cmd_vel per
    robot and step. The handler raises ValueError for a body that is no such message: the
    connection is then closed, as for a message that does not deserialise. A latched
    connection, or one handed back to rospy's own loop, still goes to the callbacks: give
    the subscriber its callback too. Replaces every callback of the topic in this process.
    """
    sub.impl.course_body_handler = handler


def _deliver(conn, receive_cb):
    """The whole messages in conn's buffer to the subscription; False if they do not
    deserialise (the socket is then closed, as rospy's receive_once does)."""
    if conn.read_buff.tell() < 4:
        return True
    handler = getattr(getattr(receive_cb, '__self__', None), 'course_body_handler', None)
    if handler is not None and not conn.is_latched:
        return _deliver_bodies(conn, handler)
    msgs = []
    try:
        conn.protocol.read_messages(conn.read_buff, msgs, conn.socket)
    except DeserializationError:
        return _refuse(conn, traceback.format_exc())
    if not msgs:
        return True
    conn.stat_num_msg += len(msgs)
    for m in msgs:
        m._connection_header = conn.header
    if conn.is_latched:
        conn.latch = msgs[-1]
    if not conn.done and not rospy.core.is_shutdown():
        receive_cb(msgs, conn)
    return True


def _deliver_bodies(conn, handler):
    """_deliver for a deliver_bodies() subscription."""
    buff = conn.read_buff
    data = buff.getvalue()[:buff.tell()]
    bodies, used = split_frames(data)
    buff.seek(0)
    buff.truncate(0)
    buff.write(data[used:])
    if not bodies:
        return True
    if conn.protocol.queue_size is not None:
        bodies = bodies[-conn.protocol.queue_size:]
    conn.stat_num_msg += len(bodies)
    if conn.done or rospy.core.is_shutdown():
        return True
    try:
        handler(bodies, conn)
    except ValueError as err:
        return _refuse(conn, 'cannot deserialize a message on %s: %s' % (conn.name, err))
    return True


def _refuse(conn, why):
    """A message that does not deserialise: logged, the socket closed (rospy's loop then
    reconnects a connection without a socket, as its receive_once does). False."""
    rospy.core.rospyerr(why)
    with contextlib.suppress(OSError):
        conn.socket.close()
    conn.socket = None
    return False


def _hand_back(conn, receive_cb):
    """The connection back to rospy's own receive loop, in a thread of its own."""
    if conn.done or rospy.core.is_shutdown():
        return
    if conn.socket is not None:
        with contextlib.suppress(OSError):
            conn.socket.setblocking(True)
    threading.Thread(target=conn.receive_loop, args=(receive_cb,), name=conn.name,
                     daemon=True).start()


def cheap_rosout():
    """Make each rospy log line cheaper without touching the parameter server.

    Replaces nothing public (rospy has no switch for it): for every line, rospy's /rosout
    handler looks up /rosout_disable_topics_generation (an XML-RPC call to the master while
    the param is unset) and, unless it is true, lists every topic of the node into the Log
    message: 3 per turtle. Seeding rospy's local parameter cache with true skips both; the
    Log's ``topics`` is then empty, which only rqt_console's topic column shows.
    """
    get_param_server_cache().set(rospy.resolve_name(ROSOUT_TOPICS_PARAM), True)


def cache_rosout_param():
    """Ask the master for /rosout_disable_topics_generation once, not on every log line.

    Replaces nothing public (rospy has no switch for it): for every log line rospy's /rosout
    handler calls ``rospy.get_param_cached(ROSOUT_TOPICS_PARAM, False)``, and while the
    parameter is unset (a plain roscore) rospy caches the master's "unset" answer as ``{}``,
    which its cache treats as missing: one subscribeParam call to the master per line, from
    every node (a talker at 10 Hz: 10 calls a second). This makes that call once
    (``rospy.get_param_cached``, public, which also subscribes the node to the parameter)
    and, if the parameter is unset, seeds the cache with rospy's own default, False. The Log
    message is unchanged (its ``topics`` still listed); a later ``rosparam set`` still
    reaches the node through the subscription. Returns the value now in the cache.
    """
    value = rospy.get_param_cached(ROSOUT_TOPICS_PARAM, None)
    if value is None:
        value = False
        get_param_server_cache().set(rospy.resolve_name(ROSOUT_TOPICS_PARAM), value)
    return value


def add_preshutdown_hook(hook):
    """Call ``hook(reason)`` when rospy starts shutting down, before its shutdown flag is set.

    Replaces ``rospy.on_shutdown``, whose hooks are not given the reason: turtlesim logs
    the reason of a ``rosnode kill`` (roscpp's two WARN lines). Nothing to measure: rospy
    has no public call that passes the reason.
    """
    rospy.core.add_preshutdown_hook(hook)


def shutdown_requested():
    """True from the moment rospy starts shutting down (before ``rospy.is_shutdown()``).

    Replaces ``rospy.is_shutdown()`` where a publisher must know that its topic may be closed:
    is_shutdown() turns true only after rospy's pre-shutdown hooks, one of which closes every
    topic, so a publish in that window raises "publish() to a closed topic". Nothing to
    measure: rospy has no public call for that window. True as well from the moment a
    SIGINT or SIGTERM arrives, under shut_down_off_the_signal.
    """
    return rospy.core.is_shutdown_requested() or _SignalShutdown.requested


class _SignalShutdown:
    """The node's SIGINT/SIGTERM: mark the request, then rospy's whole shutdown in a thread."""
    requested = False

    def __init__(self):
        self._reason = None
        self._wake = threading.Event()
        self._done = threading.Event()
        # A daemon, so that a node that never gets a signal exits as before; the exit waits
        # for it only once it has work (_wait runs before rospy's own atexit shutdown).
        threading.Thread(target=self._run, name='signal_shutdown', daemon=True).start()
        atexit.register(self._wait)

    def handle(self, signum, frame):
        if self._reason is None:
            self._reason = 'signal-%d' % signum
            _SignalShutdown.requested = True
            self._wake.set()
        # As rospy's handler: a handler set before rospy's runs too; Python's default SIGINT
        # handler's KeyboardInterrupt is dropped (the node shuts down instead).
        previous = rospy.core._signalChain.get(signum)
        if callable(previous):
            with contextlib.suppress(KeyboardInterrupt):
                previous(signum, frame)

    def _run(self):
        self._wake.wait()
        try:
            rospy.core.signal_shutdown(self._reason)
        finally:
            self._done.set()

    def _wait(self):
        if self._wake.is_set():
            self._done.wait(SIGNAL_SHUTDOWN_WAIT_S)


def shut_down_off_the_signal():
    """Make the node's SIGINT and SIGTERM run rospy's shutdown in a thread, not in the signal.

    Replaces the handler ``rospy.init_node`` installs, which runs the whole shutdown (its log
    lines, every hook, closing every connection) inside whatever the signal interrupted. If
    that was the node writing its log file, the shutdown's own lines fail ("reentrant call
    inside BufferedWriter": a "Logging error" traceback on screen at Ctrl-C); if it held a
    lock that the shutdown needs, the node hangs. This handler only marks the request
    (shutdown_requested() turns true at once, so a loop makes no further cycle) and wakes a
    thread that calls ``rospy.signal_shutdown``; the interpreter's exit waits for that thread
    up to SIGNAL_SHUTDOWN_WAIT_S. Does nothing unless rospy's own handler is in place (it is
    not under ``disable_signals=True``). Call from the main thread after rospy.init_node.
    """
    if signal.getsignal(signal.SIGINT) is not rospy.core._ros_signal:
        return
    handler = _SignalShutdown().handle
    for signum in (signal.SIGINT, signal.SIGTERM):
        if signal.getsignal(signum) is rospy.core._ros_signal:
            signal.signal(signum, handler)


def deep_tcpros_backlog():
    """Let the node's TCPROS server queue as many new connections as the kernel allows.

    Replaces nothing public (rospy has no switch for it): rospy's TCPServer listens with a
    backlog of 5, and every subscriber of every topic the node publishes connects to that
    one socket. When more than that arrive at once (stageros with 20 robots, subscribed by
    two swarm controllers: 40 connections within a second), Linux answers the rest with SYN
    cookies and then resets some ("Possible SYN flooding on port ..." in the kernel log);
    rospy takes the reset during the handshake as fatal and never connects that
    subscription again. The multi-host swarm test lost robots' scans so, about one run in
    ten. Connections that fit are accepted as before; the backlog is only a queue. Call
    before rospy.init_node (its /rosout publisher starts the server); once per process.
    """
    server_class = rospy.impl.tcpros_base.TCPServer
    if getattr(server_class._create_server_sock, 'deep_backlog', False):
        return
    create = server_class._create_server_sock

    def create_server_sock(self):
        sock = create(self)
        sock.listen(TCPROS_BACKLOG)         # a listening socket takes a new backlog
        return sock

    create_server_sock.deep_backlog = True
    server_class._create_server_sock = create_server_sock


def keep_every_publisher_update():
    """Make a subscription connect to every publisher the master has named to this node.

    Replaces nothing public (rospy has no switch for it): rospy's registration thread
    (RegManager.run) keeps, of the publisher lists still waiting for a topic, only the one
    queued last, taken to be the newest. They can be queued out of order. A subscription's
    registration (RegManager.reg_added) asks the master for the topic's publishers and
    queues the answer when the call returns; if a publisher registers in between, the
    master's publisherUpdate naming it can be queued first, and the older list without it
    wins: the subscription never connects to that publisher. Found by reading rospy while
    the multi-host swarm test lost scans (that loss was deep_tcpros_backlog's reset); a
    swarm controller subscribing while stageros registers its topics is this race's case
    too. Here a topic's list is queued merged with the lists still waiting for it, so
    nothing named is dropped. Connecting is unchanged:
    rospy's _connect_topic skips publishers already connected, and one that has left
    refuses or answers that it no longer publishes, as it would to any late subscriber.
    Call before rospy.init_node; once per process (later calls do nothing).
    """
    manager_class = rospy.impl.registration.RegManager
    if getattr(manager_class.publisher_update, 'keeps_every_update', False):
        return

    def publisher_update(self, resolved_name, uris):
        with self.cond:
            waiting = [uri for topic, listed in self.updates if topic == resolved_name
                       for uri in listed]
            self.updates.append((resolved_name, list(dict.fromkeys(waiting + list(uris)))))
            self.cond.notify_all()

    publisher_update.keeps_every_update = True
    manager_class.publisher_update = publisher_update


def name_mappings():
    """The node's command-line remappings (``from:=to``), unresolved, as a new dict.

    rospy applies them only through resolve_name, which maps whole names; turtlesim's
    turtle namespaces and mimic's ``input``/``output`` need the table itself to apply
    roscpp's namespace remapping (a remapped namespace moves every name under it). A
    lookup at start-up, so no cost is saved: rospy simply has no public call for it.
    """
    return dict(rospy.names.get_mappings())


def caller_id(msg):
    """The caller id of the node that published ``msg`` ('' if unknown).

    rospy sets ``_connection_header`` (the TCPROS header of the connection the message came
    in on) on every message it delivers, and has no public accessor for it. The monitor of
    multi_sync tells robots apart by it. A dict lookup: nothing to measure.
    """
    return getattr(msg, '_connection_header', {}).get('callerid', '')
