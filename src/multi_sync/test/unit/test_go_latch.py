"""GoLatch: GO reaches each subscriber connection exactly once, in every order of events.

The first tests feed GoLatch the events of the monitor in racy orders (no rospy). The last
two drive rospy's real publisher implementation (no master, fake transports) the way the
monitor does: with rospy's own latch a GO published while a subscriber connects reaches it
twice (the flake "2 != 1 : one GO"); with GoLatch once.
"""
import itertools

import pytest
from multi_sync.go_latch import GoLatch

GO = 'GO'


class Peer:
    """A subscriber connection: counts the GOs written to it."""

    def __init__(self, name):
        self.name = name
        self.heard = []

    def send(self, message):
        self.heard.append(message)


def run(events, peers):
    """Play events in order, as the monitor does under its lock; return the latch.

    'go' gives GO and sends it to the peers give() returns; a peer name is that peer's
    subscribe listener (rospy calls it once per new connection): it records the peer and
    sends GO to it if connected() says so.
    """
    latch = GoLatch()
    for event in events:
        if event == 'go':
            for peer in latch.give(GO):
                peer.send(GO)
        else:
            peer = peers[event]
            if latch.connected(peer):
                peer.send(latch.message)
    return latch


@pytest.mark.parametrize('events', [
    ['go', 'robot_0'],                          # subscribed after GO (a late robot)
    ['robot_0', 'go'],                          # subscribed before GO
    ['robot_0', 'test', 'go', 'robot_1'],
    # The flake's order: the last robot's listener completes the team and gives GO, then a
    # subscriber whose connection rospy had added meanwhile (the test node) runs its listener.
    ['robot_0', 'robot_1', 'go', 'test'],
])
def test_each_peer_hears_go_once(events):
    peers = {name: Peer(name) for name in ('robot_0', 'robot_1', 'test')}
    latch = run(events, peers)
    assert latch.given
    for name in events:
        if name != 'go':
            assert peers[name].heard == [GO], name


@pytest.mark.parametrize('order', list(itertools.permutations(['a', 'b', 'c', 'go'])))
def test_every_interleaving_of_three_subscribers_and_go(order):
    peers = {name: Peer(name) for name in 'abc'}
    run(order, peers)
    assert {name: len(p.heard) for name, p in peers.items()} == {'a': 1, 'b': 1, 'c': 1}


def test_nothing_is_sent_before_go():
    peers = {'a': Peer('a')}
    latch = run(['a'], peers)
    assert not latch.given and latch.message is None
    assert peers['a'].heard == []


def test_go_with_no_subscriber_yet_goes_to_nobody():
    latch = GoLatch()
    assert latch.give(GO) == []
    assert latch.connected('late') is True


@pytest.mark.parametrize('first, second, error', [
    (GO, GO, 'already given'),     # one GO per monitor
    (None, None, 'must not be None'),
])
def test_give_errors(first, second, error):
    latch = GoLatch()
    with pytest.raises(ValueError, match=error):
        latch.give(first)
        latch.give(second)


# --- the same orders through rospy's publisher (no master: fake transports) ---------------

class _Transport:
    """What rospy's _PublisherImpl needs of a connection; records the frames written."""

    def __init__(self, name):
        self.endpoint_id = name
        self.cleanup_cb = None
        self.frames = []

    def fileno(self):
        return None

    def set_cleanup_callback(self, callback):
        self.cleanup_cb = callback

    def write_data(self, data):
        self.frames.append(data)

    def close(self):
        pass


def _publisher(latch):
    rospy_topics = pytest.importorskip('rospy.topics')
    std_msgs = pytest.importorskip('std_msgs.msg')
    impl = rospy_topics._PublisherImpl('/team_status', std_msgs.String)
    if latch:
        impl.enable_latch()
    return rospy_topics, std_msgs, impl


def test_rospy_latch_sends_go_twice_to_a_peer_connecting_as_go_goes_out():
    """The cause, pinned: rospy adds the connection, runs the listeners, then sends its latch.

    The monitor before the fix published GO (latched) from its subscribe listener once the
    last robot listened, and from its status callback while other subscribers connected.
    If this starts failing, rospy changed its add_connection order: see go_latch.py.
    """
    rospy_topics, std_msgs, impl = _publisher(latch=True)

    class GoFromListener(rospy_topics.SubscribeListener):
        def peer_subscribe(self, topic_name, topic_publish, peer_publish):
            impl.acquire()  # what Publisher.publish does
            try:
                impl.publish(std_msgs.String(GO))
            finally:
                impl.release()

    impl.add_subscriber_listener(GoFromListener())
    peer = _Transport('/test_lesson')
    impl.add_connection(peer)
    assert len(peer.frames) == 2, 'rospy latch: %d GO frames' % len(peer.frames)


def test_golatch_through_rospy_sends_go_once_to_each_peer():
    """The monitor's wiring (latch off, GoLatch in the listener) in the same racy order."""
    rospy_topics, std_msgs, impl = _publisher(latch=False)
    latch = GoLatch()
    go = std_msgs.String(GO)

    class GoOnConnect(rospy_topics.SubscribeListener):
        def __init__(self, gives_go):
            super().__init__()
            self.gives_go = gives_go

        def peer_subscribe(self, topic_name, topic_publish, peer_publish):
            if latch.connected(peer_publish):
                peer_publish(latch.message)
            if self.gives_go():  # this connection completed the team: GO from the listener
                for send in latch.give(go):
                    send(go)

    first, last = _Transport('/move_robot_0'), _Transport('/move_robot_1')
    listener = GoOnConnect(lambda: not latch.given and len(impl.connections) == 2)
    impl.add_subscriber_listener(listener)
    impl.add_connection(first)
    impl.add_connection(last)
    late = _Transport('/rostopic')
    impl.add_connection(late)
    assert [len(p.frames) for p in (first, last, late)] == [1, 1, 1]
