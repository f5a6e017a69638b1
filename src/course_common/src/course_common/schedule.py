"""When things are due, for the simulators' loops and logs (pure: no rospy, no clock reads;
times come in as arguments, seconds on a monotonic clock).

- Deadlines: a loop's absolute deadlines, which do not drift (a call that runs late does not
  push the later ones back), and the one lag rule (MAX_LAG_PERIODS): turtlesim's tick and
  stageros's steps (course_common.deadline_loop runs them).
- Throttle: at most one event per period; BAD_INPUT_WARN_PERIOD_S, the period of both
  simulators' WARNs about bad input (a bad publisher can repeat at any rate).
"""
import math

from course_common.finite import check_finite

#: A loop this many periods behind (a loaded machine, a suspended process) restarts its
#: schedule from now instead of running a burst of catch-up calls, as a Qt timer does.
MAX_LAG_PERIODS = 4
#: At most one WARN about a publisher's bad input per this many seconds (per publisher/topic).
BAD_INPUT_WARN_PERIOD_S = 1.0


class Deadlines:
    """When each call is due: first at first_s, then every period_s after the last deadline.

    period_s 0 means no pacing: each call is due as soon as the last one has ended. If the
    loop falls more than max_lag_periods periods behind (a loaded machine, a suspended
    process) the schedule restarts from then instead of running a burst of catch-up calls,
    as a Qt timer does.
    """

    def __init__(self, period_s, first_s, max_lag_periods=MAX_LAG_PERIODS):
        check_finite('period_s', period_s, low=0.0)
        if not max_lag_periods >= 0:
            raise ValueError('max_lag_periods must be >= 0, not %r' % (max_lag_periods,))
        self.period_s = period_s
        self.next_s = first_s
        self.max_lag_periods = max_lag_periods

    def delay(self, now_s):
        """Seconds to wait before the next call may run (0.0 when it is due)."""
        return max(0.0, self.next_s - now_s)

    def done(self, now_s):
        """Record that the due call ended at now_s; schedules the next one."""
        if self.period_s == 0.0:
            self.next_s = now_s
            return
        self.next_s += self.period_s
        if now_s - self.next_s > self.max_lag_periods * self.period_s:
            self.next_s = now_s


class Throttle:
    """ready(now) is True at most once per period_s (the first call included)."""

    def __init__(self, period_s):
        self.period_s = period_s
        self._last = -math.inf

    def ready(self, now_s):
        if now_s - self._last >= self.period_s:
            self._last = now_s
            return True
        return False
