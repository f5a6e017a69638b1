"""stageros's stepping thread: one world step per interval_sim, paced to ~speedup x real time."""
import threading
import time

import rospy

from .pacing import FLAT_OUT, Pacer

#: Before the first step, the longest wall time given to subscribers that were already
#: waiting for stageros's topics to connect (about one step at real time).
FIRST_STEP_WAIT_S = 0.1


class StepLoop:
    """Calls node.step() on the Pacer's schedule in its own thread until stopped or shut down.

    Stops ROS when the world's quit_time is reached (Stage's quit_time ends stageros). An
    exception from a step is logged (throttled) and the loop goes on.
    """

    def __init__(self, node, speedup):
        self.node = node
        self.speedup = speedup
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name='stageros_steps', daemon=True)

    def describe(self):
        if self.speedup == FLAT_OUT:
            return 'as fast as possible'
        return 'real time' if self.speedup == 1.0 else '%g x real time' % self.speedup

    def start(self):
        self._thread.start()

    def stop(self):
        self._stop.set()

    def join(self, timeout_s):
        if self._thread.ident is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=timeout_s)

    def _run(self):
        world = self.node.world
        quit_s = world.quit_time_s if world.quit_time_s > 0 else None
        # So that nodes started before stageros get its first step (t = 0.1 s) too.
        self.node.output.wait_for_waiting_subscribers(FIRST_STEP_WAIT_S)
        pacer = Pacer(world.interval_sim_s, self.speedup, time.monotonic())
        while not self._stop.is_set() and not rospy.is_shutdown():
            delay = pacer.delay(time.monotonic())
            if delay > 0.0:
                time.sleep(delay)
                continue
            try:
                now_s = self.node.step()
            except Exception as exc:
                if self._stop.is_set() or rospy.is_shutdown():
                    break
                rospy.logerr_throttle(1.0, 'stageros step failed: %r' % (exc,))
                now_s = None
            pacer.stepped(time.monotonic())
            if quit_s is not None and now_s is not None and now_s >= quit_s - 1e-9:
                rospy.loginfo('stageros: quit_time %g s reached', quit_s)
                rospy.signal_shutdown('quit_time reached')
                break
