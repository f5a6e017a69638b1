"""turtlesim_node's wall WARNs, logged in order from their own thread."""
import collections
import threading

import rospy


class WallLog:
    """Logs turtlesim's wall WARNs from its own thread, in order.

    turtlesim warns on every tick for every turtle pushing against a wall; a rospy log line
    costs a few hundred microseconds (console, file, /rosout), so with many turtles at the
    walls logging from the tick thread would slow the 62.5 Hz tick itself. If the logger
    falls more than MAX_BACKLOG lines behind, the oldest are dropped and counted.
    """

    MAX_BACKLOG = 5000

    def __init__(self):
        self._queue = collections.deque()
        self._cond = threading.Condition()
        self._dropped = 0
        self._stopped = False
        self._thread = threading.Thread(target=self._run, name='turtlesim_walls', daemon=True)

    def start(self):
        self._thread.start()

    def stop(self):
        with self._cond:
            self._stopped = True
            self._cond.notify()

    def post(self, hits):
        """Queue the world's wall hits (each with .x and .y_s) for logging."""
        with self._cond:
            self._queue.extend(hits)
            while len(self._queue) > self.MAX_BACKLOG:
                self._queue.popleft()
                self._dropped += 1
            self._cond.notify()

    def _run(self):
        while True:
            with self._cond:
                while not self._queue and not self._stopped:
                    self._cond.wait()
                if self._stopped:
                    return
                hits = list(self._queue)
                self._queue.clear()
                dropped, self._dropped = self._dropped, 0
            if dropped:
                rospy.logwarn('(%d wall warnings dropped: too many turtles at the walls)',
                              dropped)
            for hit in hits:
                rospy.logwarn('Oh no! I hit the wall! (Clamping from [x=%f, y=%f])',
                              hit.x, hit.y_s)
