"""Pins, without a master, the rospy internals stage_lite.node.rospy_clock relies on."""
import inspect

import pytest
import rospy
import rospy.impl.simtime
import rospy.rostime
from course_common.testing import pin
from stage_lite.node import rospy_clock


def test_simtime_keeps_its_clock_subscriber_in_a_module_global():
    # The global exists only once init_simtime has run with /use_sim_time set: read the code.
    source = inspect.getsource(rospy.impl.simtime.init_simtime)
    pin('_clock_sub = rospy.topics.Subscriber(' in source, 'rospy.impl.simtime._clock_sub',
        'is the /clock subscriber init_simtime makes')


def test_no_subscription_is_reported_as_none():
    saved = getattr(rospy.impl.simtime, '_clock_sub', None)
    rospy.impl.simtime._clock_sub = None
    try:
        assert rospy_clock.drop_own_clock_subscription() is False
    finally:
        rospy.impl.simtime._clock_sub = saved


def test_a_subscription_is_unregistered_once():
    class FakeSub:
        calls = 0

        def unregister(self):
            FakeSub.calls += 1
    saved = getattr(rospy.impl.simtime, '_clock_sub', None)
    rospy.impl.simtime._clock_sub = FakeSub()
    try:
        assert rospy_clock.drop_own_clock_subscription() is True
        assert rospy_clock.drop_own_clock_subscription() is False
        assert FakeSub.calls == 1
    finally:
        rospy.impl.simtime._clock_sub = saved


@pytest.mark.filterwarnings('ignore:notifyAll:DeprecationWarning')  # rospy's own call
def test_set_own_time_is_what_rospy_reports():
    pin(callable(getattr(rospy.rostime, '_set_rostime', None)), 'rospy.rostime._set_rostime',
        'exists')
    saved = rospy.rostime._rostime_current
    try:
        rospy_clock.set_own_time(12, 300_000_000)
        assert rospy.rostime._rostime_current == rospy.Time(12, 300_000_000)  # get_rostime()
    finally:
        rospy.rostime._rostime_current = saved
