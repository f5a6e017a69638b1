"""GO for every subscriber exactly once, whenever it connects (no rospy).

Why not rospy's own latch (``Publisher(latch=True)``): rospy adds a new connection to the
publisher first, then runs the subscribe listeners, and only then sends the latched message.
A GO published in between reaches that connection twice, once with the publish and once as
the latched message. The monitor publishes GO from its subscribe listener and from its status
callback, so a subscriber connecting as GO went out (a robot, or ``rostopic echo``) heard
two GOs: multi_sync's lesson test saw "2 != 1 : one GO" on a loaded machine.

GoLatch instead keeps one send function per connection (rospy's ``peer_publish``, given to
the subscribe listener) and decides, under the caller's lock, which connections GO is sent
to: those already known when GO is given, in one pass; each later one as it connects.
"""


class GoLatch:
    """Which subscriber connections get GO, so that each gets it exactly once.

    Peers are opaque handles (the monitor uses rospy's per-connection publish functions).
    The caller serialises connected() and give() (the monitor holds its lock).
    """

    def __init__(self):
        self._waiting = []   # peers connected before GO: they get GO when it is given
        self.message = None  # GO, once given

    @property
    def given(self):
        """True once GO has been given."""
        return self.message is not None

    def connected(self, peer):
        """Record a new subscriber connection; return True if GO must be sent to it now.

        Before GO the peer is kept for give(); after GO it gets the GO that was given.
        """
        if self.message is None:
            self._waiting.append(peer)
            return False
        return True

    def give(self, message):
        """Record GO; return the peers to send it to now (each connected peer, once).

        Raises ValueError if message is None or GO was already given: one GO per monitor.
        """
        if message is None:
            raise ValueError('GO message must not be None')
        if self.message is not None:
            raise ValueError('GO was already given')
        self.message = message
        peers, self._waiting = self._waiting, []
        return peers
