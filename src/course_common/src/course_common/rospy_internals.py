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
import contextlib

import rospy
import rospy.core
import rospy.names
from rospy.impl.paramserver import get_param_server_cache

from course_common.tcpros_frames import send_frame

#: The parameter whose local cache entry cheap_rosout() seeds.
ROSOUT_TOPICS_PARAM = '/rosout_disable_topics_generation'


def tick_publisher(name, msg_class):
    """A Publisher whose new connections are plain transports, for write_frame().

    Replaces ``rospy.Publisher(name, msg_class, queue_size=N)``: rospy's queue_size wraps
    every connection in a QueuedConnection, one thread per subscriber woken for each message
    plus a sleep(0) per write. At 62.5 Hz per turtle that was most of the simulator's CPU
    (bench/turtle_lite_bench.py, CPU with 50 turtles moving). Setting ``impl.queue_size``
    to None after construction avoids rospy's warning about a missing queue_size.
    """
    pub = rospy.Publisher(name, msg_class, queue_size=1)
    pub.impl.queue_size = None
    return pub


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

    Replaces ``pub.publish(msg)``: what rospy's _PublisherImpl.publish does after
    serialising, without the per-call checks, buffer juggling and message object. The tick
    sends up to 62.5 x 2 x N messages a second and that overhead was most of the node's CPU.
    Unlike rospy's blocking sendall, a subscriber that stops reading only loses frames (as
    with roscpp's queue of 1) and never stalls the tick; a connection that fails, or took
    half a frame, is removed and closed.
    """
    impl = pub.impl
    if impl is None or impl.closed:
        return  # unregistered (killed) between the step and the publish
    for conn in impl.connections:
        try:
            if send_frame(conn.socket, frame):
                conn.stat_bytes += len(frame)
                conn.stat_num_msg += 1
        except Exception:
            with contextlib.suppress(Exception):
                impl.remove_connection(conn)
                conn.close()


def cheap_rosout():
    """Make each rospy log line cheaper without touching the parameter server.

    Replaces nothing public (rospy has no switch for it): for every line, rospy's /rosout
    handler looks up /rosout_disable_topics_generation (an XML-RPC call to the master while
    the param is unset) and, unless it is true, lists every topic of the node into the Log
    message: 3 per turtle. Seeding rospy's local parameter cache with true skips both; the
    Log's ``topics`` is then empty, which only rqt_console's topic column shows.
    """
    get_param_server_cache().set(rospy.resolve_name(ROSOUT_TOPICS_PARAM), True)


def add_preshutdown_hook(hook):
    """Call ``hook(reason)`` when rospy starts shutting down, before its shutdown flag is set.

    Replaces ``rospy.on_shutdown``, whose hooks are not given the reason: turtlesim logs
    the reason of a ``rosnode kill`` (roscpp's two WARN lines). Nothing to measure: rospy
    has no public call that passes the reason.
    """
    rospy.core.add_preshutdown_hook(hook)


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
