"""What each robot of a lesson run did: its course, why it stopped, the summary (no rospy).

stage_demo feeds it the robots' ground-truth poses and commands and the lines the run logged.
Frame: the simulator's world, metres.
"""
import math
import re

MOVED_M = 0.05  # a robot has moved once this far from its first pose (heard before GO)
STILL_MPS = 1e-3  # ground truth's speed (a finite difference over the step) once stopped
#: The monitor's lesson lines (multi_sync.monitor_node).
MONITOR_LINE = re.compile(r'^(Waiting for robots to connect\.\.\.|Robot \d+ is ready!|'
                          r'All robots GO!)$')
#: The robots' lines that say why a robot stopped (multi_sync.move_robot_node).
STOP_LINES = (re.compile(r'^Robot (\d+): (laser: obstacle|wall) .* ahead, stopping$'),
              re.compile(r'^Robot (\d+): robot \d+ is .* ahead, waiting$'))


class Track:
    """One robot's course: where it started, where it is, how far it drove, its last command."""

    def __init__(self):
        self.start = None      # (x, y) of its first pose
        self.pose = None       # (x, y) now
        self.speed_mps = None  # ground truth's speed now
        self.path_m = 0.0      # distance driven along its course
        self.last_cmd_mps = None

    def on_pose(self, x, y, speed_mps):
        """A ground-truth pose (m) and speed (m/s)."""
        if self.pose is not None:
            self.path_m += math.hypot(x - self.pose[0], y - self.pose[1])
        if self.start is None:
            self.start = (x, y)
        self.pose = (x, y)
        self.speed_mps = speed_mps

    def on_command(self, linear_mps):
        """A forward command (m/s)."""
        self.last_cmd_mps = linear_mps

    def moved(self):
        """Farther than MOVED_M from its first pose."""
        return self.start is not None and math.hypot(self.pose[0] - self.start[0],
                                                     self.pose[1] - self.start[1]) > MOVED_M

    def stopped(self):
        """Moved, now commanded 0 and standing still."""
        return self.moved() and self.last_cmd_mps == 0.0 and self.speed_mps < STILL_MPS


def stop_reasons(texts, n):
    """Each of robots 0..n-1's last log line saying why it stopped (None if it said none)."""
    reasons = [None] * n
    for text in texts:
        for pattern in STOP_LINES:
            match = pattern.match(text)
            if match and int(match.group(1)) < n:
                reasons[int(match.group(1))] = text
    return reasons


def monitor_lines(texts):
    """The monitor's lesson lines among the logged texts, in order."""
    return [t for t in texts if MONITOR_LINE.match(t)]


def summary_lines(tracks, reasons, monitor):
    """The printed summary: the monitor's lines, then one markdown row per robot."""
    lines = ['monitor: %s' % ' / '.join(monitor), '',
             '| robot | driven (m) | stopped at (x, y) m | why (its log line) |',
             '|---|---:|---|---|']
    for i, (track, reason) in enumerate(zip(tracks, reasons, strict=True)):
        x, y = track.pose
        lines.append('| robot_%d | %.2f | (%.2f, %.2f) | %s |'
                     % (i, track.path_m, x, y, reason or '(no stop line logged)'))
    return lines
