"""stageros's shortcuts past rospy's public API: its own clock (stage_lite's one such module).

stageros sets /use_sim_time before rospy.init_node (so that nodes of the same launch never
see it unset), so rospy subscribes the node to /clock: the node would receive each /clock it
publishes over a TCP connection to itself (a read, a deserialisation and a callback per step,
on the receive thread, competing with the step thread for the GIL). As the node is the
clock's source it tells rospy the time directly instead. Pinned by test/unit/test_rospy_clock.py.
"""
import rospy
import rospy.impl.simtime
import rospy.rostime


def drop_own_clock_subscription():
    """Unsubscribe rospy's own /clock subscriber, if init_node made one; True if it did.

    Replaces nothing public (rospy has no switch for it); saves one received /clock per step.
    Afterwards rospy's time stays where init_simtime put it (0) until set_own_time().
    """
    sub = getattr(rospy.impl.simtime, '_clock_sub', None)
    if sub is None:
        return False
    sub.unregister()
    rospy.impl.simtime._clock_sub = None
    return True


def set_own_time(secs, nsecs):
    """Set rospy's simulated time (what the dropped /clock subscription's callback did)."""
    rospy.rostime._set_rostime(rospy.Time(secs, nsecs))
