"""stageros's time keeping (pure, no rospy, no clock reads: times come in as arguments).

- SimClock: simulated time as a whole number of nanoseconds, one interval_sim per step, so
  stamps and the watchdog's comparisons carry no floating-point drift (0.7 - 0.5 < 0.2).
- Pacer: when each step is due on the wall clock, at ``speedup`` times real time (-1: flat
  out). Stage 4.3 runs flat out headless (rtv/Stage #89); stageros here runs in real time
  unless the world's ``speedup`` or ~speedup say otherwise. The window's Run menu changes
  the speed while it runs (faster, slower: Stage's x1.2 and x0.8), pauses and steps once.
- Watchdog: stage_ros's base_watchdog_timeout: one shared time of the last cmd_vel, in sim time.
(The WARNs about bad commands are throttled by course_common.schedule.Throttle.)
"""
import threading

from course_common.finite import check_finite, is_finite_number
from course_common.schedule import Deadlines

#: Flat out: no pacing, the next step starts when the last one is published.
FLAT_OUT = -1.0
#: Stage's Run menu: Faster multiplies the speed-up by this, Slower by SLOWER; Slower from
#: flat out goes to SLOWER_FROM_FLAT_OUT x real time (WorldGui::fasterCb, slowerCb).
FASTER, SLOWER, SLOWER_FROM_FLAT_OUT = 1.2, 0.8, 100.0
#: While paused, how often the stepping thread looks for a resume or a single step, s.
PAUSED_POLL_S = 0.02


def check_speedup(value):
    """value as a float if it is -1 (flat out) or a finite number > 0; else ValueError."""
    if not is_finite_number(value) or not (value > 0 or value == FLAT_OUT):
        raise ValueError('expected -1 (as fast as possible) or a finite number > 0')
    return float(value)


def faster(speedup):
    """Run -> Faster: x1.2; flat out stays flat out (Stage rings the bell)."""
    return FLAT_OUT if speedup == FLAT_OUT else speedup * FASTER


def slower(speedup):
    """Run -> Slower: x0.8; from flat out, 100 x real time."""
    return SLOWER_FROM_FLAT_OUT if speedup == FLAT_OUT else speedup * SLOWER


def world_speedup(value):
    """The real-time factor a world's `speedup` asks for, as Stage's window reads it: a value
    above 0 (finite), else as fast as possible (Stage's own examples write `speedup 0`)."""
    return float(value) if is_finite_number(value) and value > 0 else FLAT_OUT


class SimClock:
    """Simulated time after ``steps`` steps of interval_s each."""

    def __init__(self, interval_s):
        interval_s = check_finite('interval_sim', interval_s, low=0.0, low_open=True)
        self.interval_ns = max(1, round(interval_s * 1e9))
        self.steps = 0

    def tick(self):
        """Count one step; returns the new time in ns."""
        self.steps += 1
        return self.now_ns

    @property
    def now_ns(self):
        return self.steps * self.interval_ns

    @property
    def now_s(self):
        return self.now_ns * 1e-9

    def stamp(self):
        """(secs, nsecs) of the current time, for message headers."""
        return divmod(self.now_ns, 1_000_000_000)


class Pacer(Deadlines):
    """Wall-clock deadlines of the steps: one every interval_s / speedup seconds, the first
    at now_s; flat out, each step as soon as the last one ended.

    The window changes it from its own thread while the stepping thread reads it (a lock
    keeps the two apart): set_speedup starts the schedule again from now at the new rate;
    while paused no step is due (delay is PAUSED_POLL_S) except the ones step_once asks for.
    """

    def __init__(self, interval_s, speedup, now_s, paused=False):
        self.interval_s = interval_s
        self.speedup = check_speedup(speedup)
        self.paused = paused
        self._single_steps = 0
        self._lock = threading.Lock()
        super().__init__(self._period(), now_s)

    def _period(self):
        return 0.0 if self.speedup == FLAT_OUT else self.interval_s / self.speedup

    def restart(self, now_s):
        """The next step is due at now_s (the loop starts)."""
        with self._lock:
            self.next_s = now_s

    def set_speedup(self, speedup, now_s):
        with self._lock:
            self.speedup = check_speedup(speedup)
            self.period_s = self._period()
            self.next_s = now_s

    def set_paused(self, paused, now_s):
        with self._lock:
            if self.paused and not paused:
                self.next_s = now_s   # resume from now: no burst for the paused time
            self.paused = paused
            self._single_steps = 0

    def step_once(self):
        """While paused: one more step is due (Run -> One step)."""
        with self._lock:
            if self.paused:
                self._single_steps += 1

    def delay(self, now_s):
        with self._lock:
            if self.paused:
                return 0.0 if self._single_steps else PAUSED_POLL_S
            return super().delay(now_s)

    def done(self, now_s):
        with self._lock:
            if self.paused:
                self._single_steps = max(0, self._single_steps - 1)
            else:
                super().done(now_s)


class Watchdog:
    """Stops every robot when no cmd_vel came for timeout (sim time); <= 0 disables it.

    stageros keeps one time for all robots: a command to any robot keeps all of them going.
    """

    def __init__(self, timeout_s):
        self.timeout_ns = round(timeout_s * 1e9) if timeout_s > 0 else 0
        self.last_cmd_ns = 0

    def command(self, now_ns):
        self.last_cmd_ns = now_ns

    def expired(self, now_ns):
        """True when the robots must be stopped at this step (stageros: diff >= timeout)."""
        return self.timeout_ns > 0 and now_ns - self.last_cmd_ns >= self.timeout_ns
