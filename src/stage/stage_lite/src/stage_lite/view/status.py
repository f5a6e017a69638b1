"""The Stage window's status line (pure: no rospy, no Tk): the sim time and the real-time factor.

Stage 4.3 prints the clock as World::ClockString and WorldGui::ClockString do:
``[<h>h] <m>m <ss>s <mmm>msec [<factor>]`` with `` [ PAUSED ]`` while paused, e.g.
`` 0m 03s 200msec [1.1]``. The factor is the sim time that passed over the wall time it took,
measured here over the last RATE_WINDOW_S of wall time.
"""
from collections import deque

#: The real-time factor is measured over about this much wall time, s.
RATE_WINDOW_S = 1.0

_US_PER_HOUR = 3_600_000_000
_US_PER_MINUTE = 60_000_000
_US_PER_SECOND = 1_000_000


def clock_string(sim_ns, factor, paused):
    """Stage's status line for sim_ns of sim time, the real-time factor and the pause state."""
    usec = sim_ns // 1000
    hours = usec // _US_PER_HOUR
    minutes = (usec % _US_PER_HOUR) // _US_PER_MINUTE
    seconds = (usec % _US_PER_MINUTE) // _US_PER_SECOND
    msec = (usec % _US_PER_SECOND) // 1000
    text = ('%dh' % hours if hours > 0 else '')
    text += ' %dm %02ds %03dmsec [%.1f]' % (minutes, seconds, msec, factor)
    return text + (' [ PAUSED ]' if paused else '')


class RateMeter:
    """The real-time factor from (wall s, sim s) samples: sim time over wall time from the
    newest sample at least window_s old (or the oldest kept) to the newest; 0.0 with fewer
    than two samples."""

    def __init__(self, window_s=RATE_WINDOW_S):
        self.window_s = window_s
        self._samples = deque()

    def add(self, wall_s, sim_s):
        self._samples.append((wall_s, sim_s))
        # keep the newest sample that is at least window_s old, and all after it
        while len(self._samples) > 2 and wall_s - self._samples[1][0] >= self.window_s:
            self._samples.popleft()

    def factor(self):
        if len(self._samples) < 2:
            return 0.0
        (w0, s0), (w1, s1) = self._samples[0], self._samples[-1]
        return (s1 - s0) / (w1 - w0) if w1 > w0 else 0.0
