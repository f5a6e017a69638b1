"""stageros's stepping thread: one world step per interval_sim, paced to ~speedup x real time."""
import time

import rospy
from course_common.deadline_loop import DeadlineLoop

from . import pacing
from .pacing import FLAT_OUT, Pacer

#: Before the first step, the longest wall time given to subscribers that were already
#: waiting for stageros's topics to connect (about one step at real time).
FIRST_STEP_WAIT_S = 0.1


class StepLoop(DeadlineLoop):
    """Calls step() on the Pacer's schedule in its own thread until stopped or shut down.

    step() makes one world step and returns the sim time it reached, s; interval_s is the
    world's interval_sim; quit_time_s the world's quit_time (0: none); before_first(wait_s)
    is called once, before the first step. Stops stepping when quit_time is reached: as in
    stageros, the world stands still (the clock frozen) and the node stays up with its topics
    and services. An exception from a step is logged (throttled) and the loop goes on.

    The window's Run menu calls pause, step_once, faster, slower, realtime and flat_out from
    its own thread; ``speedup`` and ``paused`` tell what the loop does now (its Pacer's, which
    keeps the two threads apart).
    """

    def __init__(self, step, interval_s, speedup, quit_time_s=0.0, before_first=None):
        self.step = step
        self.pacer = Pacer(interval_s, speedup, time.monotonic())
        self._quit_s = quit_time_s if quit_time_s > 0 else None
        self._before_first = before_first
        super().__init__(self._step, self._schedule, 'stageros_steps', 'stageros step')

    @property
    def speedup(self):
        return self.pacer.speedup

    @property
    def paused(self):
        return self.pacer.paused

    def describe(self):
        return describe_speedup(self.speedup)

    def _schedule(self):
        # So that nodes started before stageros get its first step (t = 0.1 s) too.
        if self._before_first is not None:
            self._before_first(FIRST_STEP_WAIT_S)
        self.pacer.restart(time.monotonic())
        return self.pacer

    def _set_speedup(self, speedup):
        self.pacer.set_speedup(speedup, time.monotonic())
        rospy.loginfo('stageros: %s', self.describe())

    def pause(self, paused):
        """Run -> Pause: stop stepping (the clock stands still) or go on."""
        self.pacer.set_paused(paused, time.monotonic())

    def step_once(self):
        """Run -> One step: one step while paused (nothing otherwise)."""
        self.pacer.step_once()

    def faster(self):
        self._set_speedup(pacing.faster(self.speedup))

    def slower(self):
        self._set_speedup(pacing.slower(self.speedup))

    def realtime(self):
        self._set_speedup(1.0)

    def flat_out(self):
        self._set_speedup(FLAT_OUT)

    def _step(self):
        """One step; False once quit_time is reached (the loop ends, the node stays)."""
        now_s = self.step()
        if self._quit_s is not None and now_s is not None and now_s >= self._quit_s - 1e-9:
            rospy.loginfo('stageros: quit_time %g s reached: the world stops here, the node '
                          'stays up (as stageros)', self._quit_s)
            return False
        return True


def describe_speedup(speedup):
    if speedup == FLAT_OUT:
        return 'as fast as possible'
    return 'real time' if speedup == 1.0 else '%g x real time' % speedup
