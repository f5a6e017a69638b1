"""stageros's time keeping (pure, no rospy, no clock reads: times come in as arguments).

- SimClock: simulated time as a whole number of nanoseconds, one interval_sim per step, so
  stamps and the watchdog's comparisons carry no floating-point drift (0.7 - 0.5 < 0.2).
- Pacer: when each step is due on the wall clock, at ``speedup`` times real time (-1: flat
  out). Stage 4.3 runs flat out headless (rtv/Stage #89); stageros here runs in real time
  unless the world's ``speedup`` or ~speedup say otherwise.
- Watchdog: stage_ros's base_watchdog_timeout: one shared time of the last cmd_vel, in sim time.
(The WARNs about bad commands are throttled by course_common.schedule.Throttle.)
"""
import math

from course_common.schedule import Deadlines

#: Flat out: no pacing, the next step starts when the last one is published.
FLAT_OUT = -1.0


def check_speedup(value):
    """value as a float if it is -1 (flat out) or a finite number > 0; else ValueError."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value) or not (value > 0 or value == FLAT_OUT):
        raise ValueError('expected -1 (as fast as possible) or a finite number > 0')
    return float(value)


def world_speedup(value):
    """The real-time factor a world's `speedup` asks for, as Stage's window reads it: a value
    above 0 (finite), else as fast as possible (Stage's own examples write `speedup 0`)."""
    return float(value) if math.isfinite(value) and value > 0 else FLAT_OUT


class SimClock:
    """Simulated time after ``steps`` steps of interval_s each."""

    def __init__(self, interval_s):
        if not (math.isfinite(interval_s) and interval_s > 0):
            raise ValueError('interval_sim must be > 0 s, not %r' % (interval_s,))
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
    at now_s; flat out, each step as soon as the last one ended."""

    def __init__(self, interval_s, speedup, now_s):
        check_speedup(speedup)
        super().__init__(0.0 if speedup == FLAT_OUT else interval_s / speedup, now_s)


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
