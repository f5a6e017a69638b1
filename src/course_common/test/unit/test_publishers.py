"""Unit tests of course_common.publishers, each in a fresh interpreter (no master needed)."""
import subprocess
import sys

import pytest
from course_common.publishers import OnNewSubscriber, still_unconnected

RUN_TIMEOUT_S = 60.0  # a fresh interpreter importing rospy; generous on a loaded machine


def _run(code):
    # -W error: any warning that escapes unqueued_publisher() fails the child.
    return subprocess.run([sys.executable, '-W', 'error', '-c', code], capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S, check=False)


@pytest.mark.parametrize('kwargs, expected', [
    ('', 'None False'),
    ('latch=True', 'None True'),
])
def test_unqueued_publisher_has_no_queue_and_passes_options(kwargs, expected):
    done = _run('from std_msgs.msg import String\n'
                'from course_common.publishers import unqueued_publisher\n'
                'pub = unqueued_publisher("/unqueued", String, %s)\n'
                'print(pub.impl.queue_size, pub.impl.is_latch)\n' % kwargs)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == expected


def test_rospy_still_warns_without_queue_size_elsewhere():
    # The warning is silenced for unqueued_publisher()'s own call only.
    done = _run('import rospy\n'
                'from std_msgs.msg import String\n'
                'from course_common.publishers import unqueued_publisher\n'
                'unqueued_publisher("/unqueued", String)\n'
                'rospy.Publisher("/plain", String)\n')
    assert done.returncode != 0
    assert 'SyntaxWarning' in done.stderr
    assert 'queue_size' in done.stderr


def test_a_bad_option_is_rospys_error():
    done = _run('from std_msgs.msg import String\n'
                'from course_common.publishers import unqueued_publisher\n'
                'unqueued_publisher("/unqueued", String, no_such_option=1)\n')
    assert done.returncode != 0
    assert "unexpected keyword argument 'no_such_option'" in done.stderr


@pytest.mark.parametrize('listed, connected, earlier, missing, lost', [
    ({'/a', '/b'}, {'/a', '/b'}, set(), set(), set()),      # everyone connected
    ({'/a', '/b'}, {'/a'}, set(), {'/b'}, set()),           # /b missing once: connecting
    ({'/a', '/b'}, {'/a'}, {'/b'}, {'/b'}, {'/b'}),         # missing twice: lost
    ({'/a'}, {'/a'}, {'/b'}, set(), set()),                 # /b gone from the master
    ({'/me', '/b'}, set(), {'/me', '/b'}, {'/b'}, {'/b'}),  # this node's own subscription
])
def test_still_unconnected(listed, connected, earlier, missing, lost):
    assert still_unconnected(listed, connected, '/me', earlier) == (missing, lost)


def test_on_new_subscriber_hands_over_that_subscribers_own_send():
    sends = []
    listener = OnNewSubscriber(sends.append)

    def to_everyone(msg):
        raise AssertionError('the greeting went to every subscriber')

    def to_this_one(msg):
        return msg
    listener.peer_subscribe('/team_status', to_everyone, to_this_one)
    listener.peer_unsubscribe('/team_status', 0)  # a subscriber leaving is no new one
    assert sends == [to_this_one]
