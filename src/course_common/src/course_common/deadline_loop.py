"""A function called in its own thread on absolute deadlines (turtlesim's tick, stageros's steps).

DeadlineLoop is the thread that sleeps until each deadline of a course_common.schedule
Deadlines (the pure schedule) and makes the call.
"""
import threading
import time

import rospy

from course_common.rospy_internals import shutdown_requested

#: How often a failing call is logged at most, s (it may fail at every tick).
ERROR_LOG_PERIOD_S = 1.0


class DeadlineLoop:
    """Calls call() on a Deadlines schedule in a daemon thread until stop() (or ROS shutdown).

    schedule: called once in the thread before the first call, returns the Deadlines (it may
    wait for something first, and reads the clock itself). call() returning False ends the
    loop. An exception from call() is logged as "<what> failed: <exception>" (throttled) and
    the loop goes on, unless the loop was stopped or ROS is shutting down, which ends it.
    stop_at_shutdown: also end when ROS shuts down, without waiting for a failed call.
    clock and sleep are injected for tests.
    """

    def __init__(self, call, schedule, name, what, stop_at_shutdown=True,
                 clock=time.monotonic, sleep=time.sleep):
        self._call = call
        self._schedule = schedule
        self._what = what
        self._stop = threading.Event()
        self._stop_at_shutdown = stop_at_shutdown
        self._clock, self._sleep = clock, sleep
        self._thread = threading.Thread(target=self.run, name=name, daemon=True)

    def start(self):
        self._thread.start()

    def stop(self):
        """Ask the loop to end; it sees the request within one period."""
        self._stop.set()

    def join(self, timeout_s):
        """Wait for the loop to end (not from the loop's own thread, nor before start)."""
        if self._thread.ident is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=timeout_s)

    def _ending(self):
        # From the start of ROS's shutdown: it closes the topics before is_shutdown() is true.
        return self._stop.is_set() or shutdown_requested()

    def run(self):
        """The loop itself (the thread's body; tests call it directly)."""
        deadlines = self._schedule()
        while not self._stop.is_set() and not (self._stop_at_shutdown and shutdown_requested()):
            delay = deadlines.delay(self._clock())
            if delay > 0.0:
                # A plain sleep is cheaper than Event.wait; stop() is seen within a period.
                self._sleep(delay)
                continue
            try:
                go_on = self._call()
            except Exception as exc:
                if self._ending():
                    break
                rospy.logerr_throttle(ERROR_LOG_PERIOD_S, '%s failed: %r' % (self._what, exc))
                go_on = None
            if go_on is False:
                break
            deadlines.done(self._clock())
