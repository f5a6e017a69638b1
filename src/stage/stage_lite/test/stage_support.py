"""Helpers shared by stage_lite's rostest nodes (not a test itself).

Waiting is always on a condition with a named deadline (course_common.testing.wait_for);
the deadlines are generous for a loaded 2-core machine and cost time only on failure.
Times on topics are compared in simulated time (the stamps), never against the wall clock.
"""
import os
import subprocess
import tempfile
import threading

import rosgraph
import rospy
from course_common.testing import wait_for

START_DEADLINE_S = 40.0   # stageros coming up (Python, numpy and the world) under load
EVENT_DEADLINE_S = 20.0   # something that follows within a few simulated seconds
STEP_NS = 100_000_000     # interval_sim 100 ms
POSE_TOL_M = 1e-6         # poses come from the same doubles: only float noise
RANGE_TOL_M = 0.03        # ranges: one 2 cm ray-cast cell plus rounding
WORLDS = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'worlds')

__all__ = ['wait_for']


def world(name):
    return os.path.join(WORLDS, name)


def stamp_ns(msg):
    stamp = msg.header.stamp if hasattr(msg, 'header') else msg.clock
    return stamp.secs * 1_000_000_000 + stamp.nsecs


class Recorder:
    """Records a topic's messages in arrival order (all of them, or the newest `keep`)."""

    def __init__(self, topic, msg_class, keep=None):
        self._lock = threading.Lock()
        self._items = []
        self._keep = keep
        self.topic = topic
        self.sub = rospy.Subscriber(topic, msg_class, self._cb)

    def _cb(self, msg):
        with self._lock:
            self._items.append(msg)
            if self._keep is not None:
                del self._items[:-self._keep]

    def messages(self):
        with self._lock:
            return list(self._items)

    def count(self):
        with self._lock:
            return len(self._items)

    def latest(self):
        with self._lock:
            return self._items[-1] if self._items else None

    def clear(self):
        with self._lock:
            self._items = []

    def wait_first(self, deadline_s=START_DEADLINE_S):
        return wait_for(self.latest, deadline_s, 'a message on %s' % self.topic)

    def wait_where(self, predicate, what, deadline_s=EVENT_DEADLINE_S):
        """The first recorded message (from now on, kept ones included) satisfying predicate."""
        def found():
            return next((m for m in self.messages() if predicate(m)), None)
        return wait_for(found, deadline_s, '%s on %s' % (what, self.topic))

    def close(self):
        self.sub.unregister()


def topic_types():
    """{topic: type} of every published topic, from the master."""
    master = rosgraph.Master('/stage_test')
    return dict(master.getTopicTypes())


def service_names():
    state = rosgraph.Master('/stage_test').getSystemState()
    return {name for name, _ in state[2]}


def wait_connected(pub, what):
    wait_for(lambda: pub.get_num_connections() > 0, START_DEADLINE_S,
             '%s to connect' % what)


def run_stageros(*args, timeout_s=START_DEADLINE_S):
    """Run `rosrun stage_ros stageros ARGS` to its end: (exit code, stdout + stderr)."""
    done = subprocess.run(['rosrun', 'stage_ros', 'stageros', *args], capture_output=True,
                          text=True, timeout=timeout_s, check=False)
    return done.returncode, done.stdout + done.stderr


class _Stageros(subprocess.Popen):
    """A stageros process whose output goes to a file, readable after it ended."""

    def output(self):
        with open(self.log_path, encoding='utf-8', errors='replace') as f:
            return f.read()


def start_stageros(*args, env=None):
    """A stageros process left running (stop it with stop_process; then .output())."""
    fd, path = tempfile.mkstemp(prefix='stageros_', suffix='.log')
    with os.fdopen(fd, 'w') as log:  # the child keeps its own copy of the descriptor
        proc = _Stageros(['rosrun', 'stage_ros', 'stageros', *args], stdout=log,
                         stderr=subprocess.STDOUT, start_new_session=True, env=env)
    proc.log_path = path
    return proc


def stop_process(proc, deadline_s=EVENT_DEADLINE_S):
    """SIGINT (as Ctrl-C or roslaunch), then SIGKILL if it does not end in time."""
    if proc.poll() is None:
        os.killpg(proc.pid, 2)
        try:
            proc.wait(timeout=deadline_s)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, 9)
            proc.wait(timeout=deadline_s)
    return proc.returncode
