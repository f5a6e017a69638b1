"""Helpers for integration tests that drive turtle_lite (the rostest nodes of this workspace)."""
import time

import rospy

POLL_S = 0.01  # s between checks: fine-grained next to the 16 ms tick, cheap on the CPU


def wait_for(predicate, timeout_s, what, poll_s=POLL_S):
    """Poll predicate() until it returns a true value, and return that value.

    Raises AssertionError naming `what` when timeout_s passes first, or when ROS shuts down
    while waiting (the test's master or node is gone: waiting longer cannot help).
    """
    deadline = time.monotonic() + timeout_s
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError('timed out after %.1f s waiting for %s' % (timeout_s, what))
        if rospy.is_shutdown():
            raise AssertionError('ROS shut down while waiting for %s' % what)
        time.sleep(poll_s)
