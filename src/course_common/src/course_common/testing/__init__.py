"""Waiting with a named deadline, and pinning rospy internals: the tests' and tools' support.

Used by the rostest nodes of every package, convoy's harness and demo, and bench/.
"""
import importlib.metadata
import time

import rospy

POLL_S = 0.01  # s between checks: fine-grained next to the 16 ms tick, cheap on the CPU


class WaitError(AssertionError):
    """wait_for gave up: its deadline passed, ROS shut down, or what it needs is gone.

    An AssertionError, so a unittest reports it as a failure of the test, not an error.
    """


def wait_for(predicate, timeout_s, what, poll_s=POLL_S, alive=None):
    """Poll predicate() until it returns a true value, and return that value.

    The one wait-with-deadline of the workspace: rostest nodes, convoy's harness and demo,
    and the benchmarks use it. Raises WaitError naming `what` when timeout_s passes first,
    when ROS shuts down while waiting (the master or this node is gone: waiting longer
    cannot help), or, if `alive` is given, as soon as alive() returns a false value (the
    process being waited on has exited).
    """
    deadline = time.monotonic() + timeout_s
    while True:
        value = predicate()
        if value:
            return value
        if alive is not None and not alive():
            raise WaitError('gave up waiting for %s: the process it needs has exited' % what)
        if time.monotonic() > deadline:
            raise WaitError('timed out after %.1f s waiting for %s' % (timeout_s, what))
        if rospy.is_shutdown():
            raise WaitError('ROS shut down while waiting for %s' % what)
        time.sleep(poll_s)


def rospy_version():
    """The installed rospy's version, for messages ('unknown' if its metadata is missing)."""
    try:
        return importlib.metadata.version('rospy')
    except importlib.metadata.PackageNotFoundError:
        return 'unknown'


def pin(ok, attribute, meaning):
    """Fail, naming the rospy attribute, what it should mean and rospy's version, unless ok.

    For the tests that pin the rospy internals course_common.rospy_internals relies on.
    """
    if not ok:
        raise AssertionError('installed rospy %s: %s no longer %s (course_common.rospy_internals '
                             'relies on it)' % (rospy_version(), attribute, meaning))
