"""A ROS master in this process that records every XML-RPC call made to it (tests, benches).

Used to count what nodes ask the master, e.g. rospy's per-log-line parameter call (see
course_common.rospy_internals.cache_rosout_param): start it, point a node's ROS_MASTER_URI
at ``uri``, read ``calls``. It is rosmaster's own handler, so nodes behave as under
roscore (without the rosout node).
"""
import sys
import threading
import time

import rosgraph.xmlrpc
from rosmaster.master_api import ROSMasterHandler

START_S = 10.0  # rosmaster binds at once; generous on a loaded machine


class _Recording:
    """XML-RPC instance that records (time, method, caller id) and forwards to the handler."""

    def __init__(self, handler, master):
        self._handler = handler
        self._master = master

    def _dispatch(self, method, params):
        caller = params[0] if params and isinstance(params[0], str) else ''
        self._master.record(method, caller)
        return getattr(self._handler, method)(*params)

    def __getattr__(self, name):  # _ready, _shutdown, _ok: rosgraph's node calls them
        return getattr(self._handler, name)


class CountingMaster:
    """rosmaster on a free port, every call recorded as (monotonic time, method, caller id)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._calls = []
        self._node = rosgraph.xmlrpc.XmlRpcNode(0, _Recording(ROSMasterHandler(), self))
        self._node.start()
        deadline = time.monotonic() + START_S
        while not self._node.uri:
            if time.monotonic() > deadline:
                raise RuntimeError('the counting master did not start in %.0f s' % START_S)
            time.sleep(0.01)  # polling the server thread's start, as rosmaster.master does
        self.uri = self._node.uri
        self._print_error = self._node.server.handle_error
        self._node.server.handle_error = self._handle_error

    def _handle_error(self, request, client_address):
        # A node stopped (Ctrl-C) while its call was in flight: expected, not worth a trace.
        if not isinstance(sys.exc_info()[1], ConnectionError):
            self._print_error(request, client_address)

    def record(self, method, caller):
        with self._lock:
            self._calls.append((time.monotonic(), method, caller))

    def calls(self, caller=None, method=None, since=None):
        """The recorded (time, method, caller) calls, filtered by caller, method, time."""
        with self._lock:
            calls = list(self._calls)
        return [c for c in calls
                if (caller is None or c[2] == caller) and (method is None or c[1] == method)
                and (since is None or c[0] >= since)]

    def stop(self):
        self._node.shutdown('CountingMaster.stop')
