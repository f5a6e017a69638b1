"""Helpers shared by every turtle_lite rostest node (sim_*, tools_*, robustness_*).

Not a test itself. Waiting is always on a condition with a named deadline; the deadlines are
generous because the tests run on a loaded 2-core machine, and they only cost time when
something is wrong.
"""

import os
import select
import subprocess
import termios
import threading
import unittest
import xmlrpc.client

import rosgraph
import rosnode
import rospy
from course_common.testing import wait_for
from rosgraph_msgs.msg import Log
from std_srvs.srv import Empty
from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

START_DEADLINE_S = 30.0  # a simulator or tool process coming up (Python start-up under load)
EVENT_DEADLINE_S = 15.0  # something that should follow promptly (a pose, a log line, an exit)
# Under one 16 ms simulator tick, so a wait on the newest pose sees nearly every pose, and
# slow enough that predicates asking the master stay at 100 calls/s at the most.

#: float32 pose fields compared to this tolerance.
POSE_TOL = 1e-5
DEFAULT_BG = (69, 86, 255)
DEFAULT_PEN = (179, 184, 255)
CENTER = 5.5444446  # turtle1's start, float32
WORLD = 11.088889

#: The six graph resources of one turtle, relative to its namespace (TURTLESIM.md 1.3).
TURTLE_TOPICS = ("cmd_vel", "pose", "color_sensor")
TURTLE_SERVICES = ("set_pen", "teleport_relative", "teleport_absolute")
TURTLE_RESOURCES = TURTLE_TOPICS + TURTLE_SERVICES


class Recorder:
    """Records the messages of a topic in arrival order (the newest `keep`, or all)."""

    def __init__(self, topic, msg_class, keep=None, queue_size=None):
        self._lock = threading.Lock()
        self._items = []
        self._keep = keep
        self.topic = topic
        self.sub = rospy.Subscriber(topic, msg_class, self._cb, queue_size=queue_size)

    def _cb(self, msg):
        with self._lock:
            self._items.append(msg)
            if self._keep is not None:
                del self._items[:-self._keep]

    def clear(self):
        with self._lock:
            self._items = []

    def messages(self):
        with self._lock:
            return list(self._items)

    def count(self):
        with self._lock:
            return len(self._items)

    def latest(self):
        with self._lock:
            return self._items[-1] if self._items else None

    def close(self):
        self.sub.unregister()

    def wait_count(self, n, what=None):
        target = self.count() + n
        wait_for(lambda: self.count() >= target, EVENT_DEADLINE_S,
                 what or '%d more messages on %s' % (n, self.topic))
        return self.messages()

    def wait(self, predicate, what):
        """Wait for a message (arriving from now on) that satisfies ``predicate``."""
        start = self.count()

        def found():
            for msg in self.messages()[start:]:
                if predicate(msg):
                    return msg
            return None
        return wait_for(found, EVENT_DEADLINE_S, what)

    def wait_latest(self, predicate, what, timeout_s=EVENT_DEADLINE_S):
        """Wait until the newest message satisfies ``predicate``; return it."""
        def check():
            msg = self.latest()
            return msg if msg is not None and predicate(msg) else None
        return wait_for(check, timeout_s, f"{what} on {self.topic}")


class PoseRecorder(Recorder):
    def __init__(self, topic='/turtle1/pose', keep=None):
        super().__init__(topic, Pose, keep)

    def wait_at_rest(self):
        return self.wait(lambda p: p.linear_velocity == 0 and p.angular_velocity == 0,
                         '%s at rest' % self.topic)


class ColorRecorder(Recorder):
    def __init__(self, topic='/turtle1/color_sensor'):
        super().__init__(topic, Color)

    def wait_rgb(self, rgb, what):
        return self.wait(lambda c: (c.r, c.g, c.b) == tuple(rgb), what)


class LogRecorder(Recorder):
    """/rosout messages of one node (rostest runs no rosout aggregator).

    Construct it after the nodes of interest are up: it waits until it is connected to every
    node that publishes /rosout, so later log lines cannot be missed.
    """

    def __init__(self, node='/turtlesim'):
        self.node = node
        super().__init__('/rosout', Log, queue_size=1000)
        wait_for(lambda: self.sub.get_num_connections() >= len(_publishers('/rosout')),
                 START_DEADLINE_S, 'connections to every /rosout publisher')

    def records(self, level=None):
        """The Log messages of the node, at ``level`` if given."""
        return [m for m in self.messages()
                if m.name == self.node and (level is None or m.level == level)]

    def lines(self, level=None):
        return [m.msg for m in self.records(level)]

    def wait_log(self, text, level=None):
        """Wait until a line containing ``text`` has been logged; return its Log message."""
        def found():
            for msg in self.records(level):
                if text in msg.msg:
                    return msg
            return None
        return wait_for(found, EVENT_DEADLINE_S, 'log line %r from %s' % (text, self.node))

    def wait_line(self, text, level=None):
        """Wait until a line containing ``text`` has been logged; return the line."""
        return self.wait_log(text, level).msg


class SimTestCase(unittest.TestCase):
    """A TestCase against one turtlesim_node at the root namespace (the node is rospy's).

    setUpClass waits for the simulator's services and makes the proxies below; with
    RECORD_TURTLE1 (the default) it also records turtle1's pose, colour and the simulator's
    log, and waits for the first pose.
    """

    RECORD_TURTLE1 = True

    @classmethod
    def setUpClass(cls):
        for name in ('/clear', '/reset', '/spawn', '/kill'):
            rospy.wait_for_service(name, START_DEADLINE_S)
        cls.reset = rospy.ServiceProxy('/reset', Empty)
        cls.clear = rospy.ServiceProxy('/clear', Empty)
        cls.spawn = rospy.ServiceProxy('/spawn', Spawn)
        cls.kill = rospy.ServiceProxy('/kill', Kill)
        cls.set_pen = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
        cls.absolute = rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)
        cls.relative = rospy.ServiceProxy('/turtle1/teleport_relative', TeleportRelative)
        if cls.RECORD_TURTLE1:
            cls.pose = PoseRecorder()
            cls.color = ColorRecorder()
            cls.logs = LogRecorder()
            wait_for(lambda: cls.pose.count() > 0, START_DEADLINE_S, 'the first pose')


class Tool:
    """A ROS process run by the test (so its output and exit code can be observed).

    stdout and stderr are merged and collected line by line in a thread; the process runs
    unbuffered so log lines arrive as they are written.
    """

    def __init__(self, argv, env_extra=None, **popen_kwargs):
        env = dict(os.environ, PYTHONUNBUFFERED="1")
        env.update(env_extra or {})
        self._lock = threading.Lock()
        self._lines = []
        self.proc = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True, **popen_kwargs)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        for line in self.proc.stdout:
            with self._lock:
                self._lines.append(line.rstrip("\n"))

    def output(self):
        with self._lock:
            return list(self._lines)

    def lines_with(self, text):
        return [line for line in self.output() if text in line]

    def wait_line(self, text, timeout_s=EVENT_DEADLINE_S):
        """Wait for an output line containing text; return the first one."""
        found = wait_for(lambda: self.lines_with(text), timeout_s, f"output line {text!r}")
        return found[0]

    def wait_exit(self, timeout_s=EVENT_DEADLINE_S):
        """Wait for the process to end; return its exit code (AssertionError if it does not)."""
        try:
            code = self.proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired as err:
            raise AssertionError(f"process {self.proc.args} still running after "
                                 f"{timeout_s:.0f} s") from err
        self._reader.join(timeout=EVENT_DEADLINE_S)
        return code

    def stop(self):
        """Make sure the process is gone (test clean-up)."""
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=EVENT_DEADLINE_S)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()


class PtyTeleop:
    """turtle_teleop_key (or argv) with a pseudo-terminal as stdin/stdout/stderr."""

    def __init__(self, env_extra=None, argv=("rosrun", "turtle_lite", "turtle_teleop_key")):
        self.master, self.slave = os.openpty()
        self._out = b""
        self._lock = threading.Lock()
        self.proc = subprocess.Popen(list(argv),
                                     stdin=self.slave, stdout=self.slave, stderr=self.slave,
                                     start_new_session=True,
                                     env=dict(os.environ, **(env_extra or {})))
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        fd = self.master
        while True:
            try:
                ready, _, _ = select.select([fd], [], [], 0.1)
                data = os.read(fd, 1024) if ready else b""
            except (OSError, ValueError):  # the test hung up, or the teleop side closed
                return
            if ready:
                with self._lock:
                    self._out += data
            elif self.proc.poll() is not None:
                return

    def output(self):
        with self._lock:
            return self._out.decode(errors="replace")

    def send(self, data):
        os.write(self.master, data)

    def lflags(self):
        return termios.tcgetattr(self.slave)[3]

    def hang_up(self):
        """Close the terminal's master side, as when a terminal window is closed."""
        os.close(self.master)
        self.master = None

    def close(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if self.master is not None:
            os.close(self.master)
        os.close(self.slave)


def wait_connected(pub, what):
    """Wait until the publisher has a subscriber."""
    wait_for(lambda: pub.get_num_connections() > 0, START_DEADLINE_S, what)


def master():
    return rosgraph.Master(rospy.get_name())


def graph_names():
    """(set of topics with a publisher or subscriber, set of services) from the master."""
    pubs, subs, services = master().getSystemState()
    topics = {name for name, _ in pubs} | {name for name, _ in subs}
    return topics, {name for name, _ in services}


def _publishers(topic):
    for name, nodes in master().getSystemState()[0]:
        if name == topic:
            return nodes
    return []


def published_topics():
    return {name for name, _ in master().getSystemState()[0]}


def subscribed_topics():
    return {name for name, _ in master().getSystemState()[1]}


def services():
    return graph_names()[1]


def turtle_graph_names(namespace):
    """The full (topic set, service set) of the turtle whose namespace is ``namespace``."""
    return ({f"{namespace}/{t}" for t in TURTLE_TOPICS},
            {f"{namespace}/{s}" for s in TURTLE_SERVICES})


def names_under(prefix):
    """Topics and services on the master below ``prefix`` (a namespace such as /robot1)."""
    topics, svcs = graph_names()
    return {n for n in topics | svcs if n.startswith(prefix + '/')}


def has_turtle_at(namespace):
    """True when all six resources of a turtle are on the master under ``namespace``."""
    topics, svcs = turtle_graph_names(namespace)
    return names_under(namespace) >= topics | svcs


def publisher_has_connected(node, topic):
    """True once `node`'s publisher of `topic` lists its connection to this test node.

    rospy counts a connection on the subscriber side before the publisher side has added
    it, and a message published in between is lost; a test that counts messages waits for
    the publisher's side (its getBusInfo) first.
    """
    try:
        uri = master().lookupNode(node)
        code, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo(rospy.get_name())
    except (rosgraph.MasterError, OSError):
        return False
    return code == 1 and any(c[1] == rospy.get_name() and c[2] == "o" and c[4] == topic
                             for c in info)


def kill_node(name):
    """rosnode kill: ask the node to shut down through its XML-RPC API."""
    _, failed = rosnode.kill_nodes([name])
    if failed:
        raise AssertionError(f"rosnode kill {name} failed")
