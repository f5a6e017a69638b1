"""ros_net_check on hosts with the classic network mistakes, and the symptom it explains.

Master on host 1; a publisher (rostopic pub) on host 2, configured well or badly.
"""
from course_common.testing import wait_for
from multihost.lessons import start_master

CHECK = ['rosrun', 'multihost', 'ros_net_check', '--timeout', '1']
SILENCE_S = 5.0  # an echo that hears nothing for this long: the publisher is unreachable


def _publisher(team, extra_env=None):
    """A /chatter publisher on host 2; returns once the master lists it."""
    team.start('talker', 2, ['rostopic', 'pub', '-r', '5', '/chatter', 'std_msgs/String', 'hi'],
               extra_env)
    wait_for(lambda: '/chatter' in team.run(1, ['rostopic', 'list'])[1], 30.0,
             '/chatter to be listed on host 1')


def test_good_team_is_all_ok(team):
    start_master(team, ['robot1'])
    _publisher(team)
    status, out = team.run(3, [*CHECK, '--hosts', 'host1', 'host2'])
    assert status == 0, out
    assert 'this host advertises http://10.77.0.3:<port>/ (from ROS_IP)' in out
    assert 'ok   master http://10.77.0.1:11311 answers' in out
    assert 'reachable' in out and 'all ok' in out


def test_unresolvable_hostname_listed_but_silent_then_explained(team):
    start_master(team, ['robot1'])
    _publisher(team, {'ROS_HOSTNAME': 'ghost-laptop'})
    # The symptom: host 1 lists the topic, yet receives nothing from it.
    status, out = team.run(1, ['timeout', str(SILENCE_S), 'rostopic', 'echo', '-n', '1',
                               '/chatter'], timeout_s=SILENCE_S + 30.0)
    assert 'data: "hi"' not in out, out
    # The explanation on host 1 ...
    status, out = team.run(1, CHECK)
    assert status == 1, out
    assert 'advertises http://ghost-laptop:' in out
    assert "'ghost-laptop' does not resolve here" in out
    assert 'add "<its address> ghost-laptop" to /etc/hosts' in out
    # ... and on host 2, with the exact fix.
    status, out = team.run(2, CHECK, {'ROS_HOSTNAME': 'ghost-laptop'})
    assert status == 1, out
    assert 'FAIL ROS_HOSTNAME=ghost-laptop does not resolve' in out
    assert 'fix: export ROS_IP=10.77.0.2' in out


def test_wrong_ros_ip(team):
    start_master(team, ['robot1'])
    status, out = team.run(2, CHECK, {'ROS_IP': '10.77.0.3'})
    assert status == 1, out
    assert 'FAIL ROS_IP=10.77.0.3 is not an address of this host (its addresses: 10.77.0.2' in out
    assert 'fix: export ROS_IP=10.77.0.2' in out


def test_localhost_on_a_team(team):
    start_master(team, ['robot1'])
    status, out = team.run(2, CHECK, {'ROS_HOSTNAME': 'localhost'})
    assert status == 1, out
    assert 'FAIL ROS_HOSTNAME=localhost is a loopback name' in out
    assert 'fix: unset ROS_HOSTNAME; export ROS_IP=10.77.0.2' in out


def test_unreachable_master(team, hosts3):
    # No roscore yet: refused.
    status, out = team.run(2, CHECK)
    assert status == 1, out
    assert 'FAIL master http://10.77.0.1:11311 not reachable: Connection refused' in out
    assert 'roscore runs on 10.77.0.1' in out
    # The master's host named by a loopback name.
    status, out = team.run(2, CHECK, {'ROS_MASTER_URI': 'http://localhost:11311'})
    assert status == 1 and 'roscore runs on this host' in out, out
    # A master host no one can resolve.
    status, out = team.run(2, CHECK, {'ROS_MASTER_URI': 'http://masterpc:11311'})
    assert status == 1 and "master host 'masterpc'" in out, out
    # Master running, but host 2's cable out: no answer at all.
    start_master(team, ['robot1'])
    hosts3.link(2, up=False)
    try:
        status, out = team.run(2, CHECK)
    finally:
        hosts3.link(2, up=True)
    assert status == 1 and 'not reachable: no answer within 1.0 s' in out, out
