"""turtlesim_node's tick thread: a function called on absolute deadlines, like a Qt timer."""
import threading
import time

import rospy

#: If the thread falls this many periods behind (machine suspended or overloaded) it
#: re-anchors its schedule instead of firing a burst of catch-up ticks, as a Qt timer does.
MAX_LAG_TICKS = 4


class TickLoop:
    """Calls tick() every period_s seconds on deadlines that do not drift, in its own thread.

    An exception from tick() is logged (throttled) and the loop goes on, unless the loop
    was stopped or ROS is shutting down, which ends it.
    """

    def __init__(self, tick, period_s, name):
        self._tick = tick
        self._period_s = period_s
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)

    def start(self):
        self._thread.start()

    def stop(self):
        """Ask the loop to end; it sees the request within one period."""
        self._stop.set()

    def join(self, timeout_s):
        """Wait for the loop to end (not from the loop's own thread, nor before start)."""
        if self._thread.ident is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=timeout_s)

    def _run(self):
        next_tick = time.monotonic()
        while not self._stop.is_set():
            next_tick += self._period_s
            delay = next_tick - time.monotonic()
            if delay > 0.0:
                # A plain sleep is cheaper than Event.wait; stop() is seen within a tick.
                time.sleep(delay)
                if self._stop.is_set():
                    break
            elif delay < -MAX_LAG_TICKS * self._period_s:
                next_tick = time.monotonic()
            try:
                self._tick()
            except Exception as exc:
                if self._stop.is_set() or rospy.is_shutdown():
                    break
                rospy.logerr_throttle(1.0, 'turtlesim tick failed: %r' % exc)
