"""wait_for: the workspace's one wait on a condition with a named deadline.

Not test code: convoy's harness and demo, rviz_snapshot and multihost's lessons wait with it
too, so it lives outside course_common.testing (which re-exports it for the tests).
A program that never imported rospy (the browser desktop) waits with it too, without paying
for rospy's import: ROS shutting down can only end a wait in a process that uses ROS.
"""
import sys
import time

POLL_S = 0.01  # s between checks: fine-grained next to the 16 ms tick, cheap on the CPU


class WaitError(AssertionError):
    """wait_for gave up: its deadline passed, ROS shut down, or what it needs is gone.

    An AssertionError, so a unittest reports it as a failure of the test, not an error.
    """


def wait_for(predicate, timeout_s, what, poll_s=POLL_S, alive=None):
    """Poll predicate() until it returns a true value, and return that value.

    Raises WaitError naming `what` when timeout_s passes first, when ROS shuts down while
    waiting (the master or this node is gone: waiting longer cannot help), or, if `alive` is
    given, as soon as alive() returns a false value (the process being waited on has exited).
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
        rospy = sys.modules.get('rospy')
        if rospy is not None and rospy.is_shutdown():
            raise WaitError('ROS shut down while waiting for %s' % what)
        time.sleep(poll_s)
