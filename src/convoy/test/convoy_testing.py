"""Shared helpers of the convoy integration tests: condition waits and a pose watcher."""
import math
import threading

import rospy
from course_common.testing import wait_for
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

TOLERANCE_M = 1.5  # the course's distance_tolerance (convoy_node's default)
# A follower has caught up when it is within the tolerance plus half a metre of its leader.
CAUGHT_UP_M = TOLERANCE_M + 0.5
# Stated convoy gap once caught up, with the autopilot's 0.5 m/s: speed / Kp_lv = 1.67 m on a
# straight; curves open it a little. Above this the convoy is broken, not just slow.
STATED_GAP_M = 2.5
LEFT_START_M = 1.0  # a follower that moved this far from its spawn point has left the corner


def distance(a, b):
    return math.hypot(a.x - b.x, a.y - b.y)


class ConvoyWatch:
    """Latest pose and command of robot1..robot<n>, plus per-robot counters and start poses."""

    def __init__(self, n_robots):
        self._lock = threading.Lock()
        self.n_robots = n_robots
        self._pose = {}
        self._first = {}
        self._count = {}
        self._cmd = {}
        self._travelled = {}
        self._subs = []
        for i in range(1, n_robots + 1):
            self._subs.append(rospy.Subscriber('/robot%d/pose' % i, Pose, self._on_pose, i))
            self._subs.append(rospy.Subscriber('/robot%d/cmd_vel' % i, Twist, self._on_cmd, i))

    def _on_pose(self, msg, robot):
        with self._lock:
            previous = self._pose.get(robot)
            if previous is not None:
                self._travelled[robot] = self._travelled.get(robot, 0.0) + distance(previous, msg)
            self._pose[robot] = msg
            self._first.setdefault(robot, msg)
            self._count[robot] = self._count.get(robot, 0) + 1

    def _on_cmd(self, msg, robot):
        with self._lock:
            self._cmd[robot] = msg

    def pose(self, robot):
        with self._lock:
            return self._pose.get(robot)

    def command(self, robot):
        with self._lock:
            return self._cmd.get(robot)

    def count(self, robot):
        with self._lock:
            return self._count.get(robot, 0)

    def travelled(self, robot):
        """Path length (m) robot<robot> has driven since its first pose."""
        with self._lock:
            return self._travelled.get(robot, 0.0)

    def all_seen(self):
        with self._lock:
            return len(self._pose) == self.n_robots

    def gap(self, follower):
        """Distance from robot<follower> to robot<follower - 1>, or inf if unknown."""
        with self._lock:
            a, b = self._pose.get(follower), self._pose.get(follower - 1)
        return math.inf if a is None or b is None else distance(a, b)

    def left_start(self, robot):
        with self._lock:
            first, now = self._first.get(robot), self._pose.get(robot)
        return first is not None and distance(first, now) > LEFT_START_M

    def caught_up(self, follower):
        return self.left_start(follower) and self.gap(follower) <= CAUGHT_UP_M

    def worst_gaps_over(self, followers, poses, timeout_s):
        """Largest gap of each follower over the next `poses` poses of the last follower."""
        worst = {f: 0.0 for f in followers}
        last = followers[-1]
        target = self.count(last) + poses
        seen = self.count(last)

        def sample():
            nonlocal seen
            now = self.count(last)
            if now != seen:
                seen = now
                for f in followers:
                    worst[f] = max(worst[f], self.gap(f))
            return now >= target
        wait_for(sample, timeout_s, '%d more poses of robot%d' % (poses, last))
        return worst
