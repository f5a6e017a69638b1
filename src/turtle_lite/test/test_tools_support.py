"""Shared helpers for the tools_* and robustness_* rostest nodes (not a test itself).

Waiting is always on a condition with a named deadline; the deadlines are generous because
the tests run on a loaded 2-core machine, and they only cost time when something is wrong.
"""

import os
import subprocess
import threading
import time
import xmlrpc.client

import rosgraph
import rosnode
import rospy
from rosgraph_msgs.msg import Log

from turtle_lite.msg import Pose

START_DEADLINE_S = 30.0  # a simulator or tool process coming up (Python start-up under load)
EVENT_DEADLINE_S = 15.0  # something that should follow promptly (a pose, a log line, an exit)
POLL_S = 0.02


def wait_for(predicate, timeout_s, what):
    """Poll predicate until it returns a true value; return that value.

    Raises AssertionError naming `what` when timeout_s passes first.
    """
    deadline = time.monotonic() + timeout_s
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout_s:.0f} s waiting for {what}")
        time.sleep(POLL_S)


class PoseWatcher:
    """Keeps the poses received on one topic (the newest ones, up to `keep`)."""

    def __init__(self, topic, keep=2000):
        self._lock = threading.Lock()
        self._poses = []
        self._keep = keep
        self.topic = topic
        self._sub = rospy.Subscriber(topic, Pose, self._on_pose, queue_size=100)

    def _on_pose(self, msg):
        with self._lock:
            self._poses.append(msg)
            del self._poses[:-self._keep]

    def poses(self):
        with self._lock:
            return list(self._poses)

    def latest(self):
        with self._lock:
            return self._poses[-1] if self._poses else None

    def count(self):
        with self._lock:
            return len(self._poses)

    def clear(self):
        with self._lock:
            self._poses = []

    def wait_pose(self, predicate, what, timeout_s=EVENT_DEADLINE_S):
        """Wait for a newest pose satisfying predicate(pose); return it."""
        def check():
            pose = self.latest()
            return pose if pose is not None and predicate(pose) else None
        return wait_for(check, timeout_s, f"{what} on {self.topic}")

    def close(self):
        self._sub.unregister()


class LogWatcher:
    """Collects (node name, level, text) from /rosout (rostest runs no rosout aggregator).

    Construct it after the nodes of interest are up: it waits until it is connected to every
    node that publishes /rosout, so later log lines cannot be missed.
    """

    def __init__(self):
        self._lock = threading.Lock()
        self._records = []
        self._sub = rospy.Subscriber("/rosout", Log, self._on_log, queue_size=1000)
        wait_for(lambda: self._sub.get_num_connections() >= len(_publishers("/rosout")),
                 START_DEADLINE_S, "connections to every /rosout publisher")

    def _on_log(self, msg):
        with self._lock:
            self._records.append((msg.name, msg.level, msg.msg))

    def matching(self, text, node=None):
        with self._lock:
            return [r for r in self._records if text in r[2] and node in (None, r[0])]

    def wait_log(self, text, node=None, timeout_s=EVENT_DEADLINE_S):
        """Wait for a log record containing text (from node, if given); return it."""
        return wait_for(lambda: self.matching(text, node), timeout_s,
                        f"a log line {text!r}")[0]

    def close(self):
        self._sub.unregister()


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
