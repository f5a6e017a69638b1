"""convoy across hosts: simulator and autopilot leader on host 1, convoy_node (robot1 ->
robot2) on host 2, convoy2_node (robot2 -> robot3) on host 3. Seen from host 1 by a probe."""
import time

from course_common.testing import wait_for
from multihost.lessons import start_convoy

CAUGHT_UP_M = 2.0   # the course's 1.5 m tolerance plus half a metre (as convoy's own tests)
STATED_GAP_M = 2.5  # convoy's stated gap once caught up with the autopilot's 0.5 m/s
CATCH_UP_S = 90.0   # from the corner, ~12 s of turtle time; margin for a loaded machine
STOP_S = 5.0        # cut -> follower still: the simulator's 1 s timeout plus load margin
STILL_S = 0.5       # no pose change for this long = stopped
OUTAGE_S = 3.0      # the cable stays out this long after the follower stopped
REJOIN_S = 30.0     # restore -> moving again (TCP retransmission back-off)


def _caught_up(probe):
    for leader, follower in (('robot1', 'robot2'), ('robot2', 'robot3')):
        wait_for(lambda a=leader, b=follower: (probe.gap(a, b) or 99.0) < CAUGHT_UP_M,
                 CATCH_UP_S, '%s to come within %.1f m of %s' % (follower, CAUGHT_UP_M, leader))


def test_followers_on_their_own_hosts_catch_up(team):
    probe = start_convoy(team)
    _caught_up(probe)
    assert not team.exited(), 'processes ended: %s' % team.exited()
    assert not team.stop(), 'processes ignored Ctrl-C'


def test_follower_host_cut_and_restored(team, hosts3):
    probe = start_convoy(team)
    _caught_up(probe)
    hosts3.link(3, up=False)
    cut = time.time()
    try:
        wait_for(lambda: probe.still('robot3', STILL_S), STOP_S,
                 'robot3 (its convoy2_node on host 3, cable out) to stop')
        stopped_at = probe.last_change('robot3')
        stopped_ms = 1000.0 * (stopped_at - cut)
        # Throughout the outage the rest of the convoy keeps formation.
        outage_end = time.monotonic() + OUTAGE_S
        while time.monotonic() < outage_end:
            wait_for(lambda: probe.moving('robot2', STILL_S), 2.0, 'robot2 to keep following')
            assert probe.gap('robot1', 'robot2') < STATED_GAP_M, 'robot2 lost robot1'
            assert probe.last_change('robot3') == stopped_at, \
                'robot3 moved while its cable was out'
            time.sleep(STILL_S / 2)  # sampling period of the checks above, not a wait
    finally:
        hosts3.link(3, up=True)
    restored = time.time()
    wait_for(lambda: (probe.last_change('robot3') or 0.0) > restored, REJOIN_S,
             'robot3 to move again after the cable is back')
    wait_for(lambda: (probe.gap('robot2', 'robot3') or 99.0) < CAUGHT_UP_M, CATCH_UP_S,
             'robot3 to catch up with robot2 again')
    print('cut -> robot3 stopped: %.0f ms' % stopped_ms)
    assert not team.exited(), 'processes ended: %s' % team.exited()
    assert not team.stop(), 'processes ignored Ctrl-C'
