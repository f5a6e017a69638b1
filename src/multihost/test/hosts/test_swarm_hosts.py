"""A Stage swarm across hosts: stageros on host 1 (swarm.launch controller:=false), robots
0-9 driven by a swarm_controller on host 2, robots 10-19 by one on host 3, every robot's
ground truth seen from host 1 by a probe."""
from course_common.testing import wait_for
from multihost.lessons import start_swarm

ROBOTS = 20
DRIVEN_S = 90.0  # master, stageros, two controllers and 40 subscriptions on a loaded machine


def test_swarm_split_over_two_controller_hosts(team):
    probe = start_swarm(team, ROBOTS, speedup=2.0)
    names = ['robot_%d' % i for i in range(ROBOTS)]

    def unmoved():
        return [n for n in names if probe.last_change(n) is None]
    wait_for(lambda: not unmoved(), DRIVEN_S,
             'every robot to move, each half driven from its own host')
    for name in ('swarm_a', 'swarm_b'):
        log = team.tail(name, 200)
        assert 'every robot\'s first scan received: 10 robots' in log, log
    assert 'driving 10 robots (robot_0 to robot_9)' in team.tail('swarm_a', 200)
    assert 'driving 10 robots (robot_10 to robot_19)' in team.tail('swarm_b', 200)
    assert not team.exited(), 'processes ended: %s' % team.exited()
    assert not team.stop(), 'processes ignored Ctrl-C'
