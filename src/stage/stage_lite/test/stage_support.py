"""Helpers shared by stage_lite's rostest nodes (not a test itself).

Waiting is always on a condition with a named deadline (course_common.testing.wait_for);
the deadlines are generous for a loaded 2-core machine and cost time only on failure.
Times on topics are compared in simulated time (the stamps), never against the wall clock.
"""
import os
import unittest

import rospy
from course_common.processes import run_to_exit
from course_common.testing import spawn, wait_for
from course_common.testing.master import services as service_names
from course_common.testing.master import topic_types
from course_common.testing.recorders import Recorder as TopicRecorder

START_DEADLINE_S = 40.0   # stageros coming up (Python, numpy and the world) under load
EVENT_DEADLINE_S = 20.0   # something that follows within a few simulated seconds
STEP_NS = 100_000_000     # interval_sim 100 ms
POSE_TOL_M = 1e-6         # poses come from the same doubles: only float noise
RANGE_TOL_M = 0.03        # ranges: one 2 cm ray-cast cell plus rounding
WORLDS = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'worlds')
STAGEROS = ['rosrun', 'stage_ros', 'stageros']

__all__ = ['service_names', 'topic_types', 'wait_for']  # re-exported for the test nodes


class StageTestCase(unittest.TestCase):
    """A stage test node's TestCase: its node (NODE_NAME) is initialised once per class."""

    NODE_NAME = None

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        rospy.init_node(cls.NODE_NAME)


def world(name):
    return os.path.join(WORLDS, name)


class Recorder(TopicRecorder):
    """course_common's Recorder with the waits the stage tests use."""

    def wait_first(self, deadline_s=START_DEADLINE_S):
        return wait_for(self.latest, deadline_s, 'a message on %s' % self.topic)

    def wait_where(self, predicate, what, deadline_s=EVENT_DEADLINE_S):
        """The first recorded message (from now on, kept ones included) satisfying predicate."""
        def found():
            return next((m for m in self.messages() if predicate(m)), None)
        return wait_for(found, deadline_s, '%s on %s' % (what, self.topic))


def wait_connected(pub, what):
    wait_for(lambda: pub.get_num_connections() > 0, START_DEADLINE_S,
             '%s to connect' % what)


def run_stageros(*args, timeout_s=START_DEADLINE_S):
    """Run `rosrun stage_ros stageros ARGS` to its end: (exit code, its output)."""
    return run_to_exit([*STAGEROS, *args], timeout_s)


def start_stageros(*args, env=None):
    """A running stageros (a ChildProcess: stop() it; output() any time).

    env: variables changed for it (a value None removes one)."""
    return spawn([*STAGEROS, *args], env=env, stop_timeout_s=EVENT_DEADLINE_S)
