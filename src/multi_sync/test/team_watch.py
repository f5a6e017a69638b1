"""Helpers for multi_sync's rostest nodes: watch a team on its topics, run nodes, wait."""
import threading
import time

import rospy
from course_common.processes import ChildProcess
from course_common.testing import rosrun_once
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from turtlesim.msg import Pose

from multi_sync.msg import RobotPosition, RobotStatus


class TeamWatch:
    """Records what a user would see of robots 0..n-1: poses, commands, statuses, logs."""

    def __init__(self, n, namespace=''):
        self.n = n
        self.lock = threading.Lock()
        self.first_pose = {}
        self.pose = {}
        self.last_cmd = {}
        self.first_move_wall = {}    # robot id -> wall time of its first non-zero cmd_vel
        self.ready_counts = {}       # robot id -> ready reports seen on team_status
        self.go_msgs = []            # (receive wall time, msg) of every GO
        self.position_ids = set()    # robot ids seen on team_positions
        self.logs = []               # (node name, text) from /rosout
        ns = namespace.rstrip('/') + '/' if namespace else ''
        self._subs = [rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)]
        for i in range(n):
            self._subs.append(rospy.Subscriber('%srobot_%d/pose' % (ns, i), Pose,
                                               self._on_pose, i, queue_size=1))
            self._subs.append(rospy.Subscriber('%srobot_%d/cmd_vel' % (ns, i), Twist,
                                               self._on_cmd, i, queue_size=10,
                                               tcp_nodelay=True))
        self._subs.append(rospy.Subscriber(ns + 'team_status', RobotStatus, self._on_status,
                                           queue_size=1000, tcp_nodelay=True))
        self._subs.append(rospy.Subscriber(ns + 'team_positions', RobotPosition,
                                           self._on_position, queue_size=1000))

    def close(self):
        for sub in self._subs:
            sub.unregister()

    def _on_log(self, msg):
        with self.lock:
            self.logs.append((msg.name, msg.msg))

    def _on_pose(self, msg, i):
        with self.lock:
            self.first_pose.setdefault(i, (msg.x, msg.y))
            self.pose[i] = (msg.x, msg.y, msg.theta)

    def _on_cmd(self, msg, i):
        with self.lock:
            self.last_cmd[i] = msg.linear.x
            if msg.linear.x != 0.0:
                self.first_move_wall.setdefault(i, time.time())

    def _on_status(self, msg):
        with self.lock:
            if msg.header.frame_id == 'monitor':
                self.go_msgs.append((time.time(), msg))
            elif msg.is_ready:
                self.ready_counts[msg.robot_id] = self.ready_counts.get(msg.robot_id, 0) + 1

    def _on_position(self, msg):
        with self.lock:
            self.position_ids.add(msg.robot_id)

    # --- predicates ------------------------------------------------------------------------
    def ids(self):
        return range(self.n)

    def have_poses(self):
        with self.lock:
            return all(i in self.pose for i in self.ids())

    def announced(self, times):
        with self.lock:
            return all(self.ready_counts.get(i, 0) >= times for i in self.ids())

    def moved(self, ids=None):
        with self.lock:
            return all(i in self.first_move_wall for i in (self.ids() if ids is None else ids))

    def stopped(self):
        """Every robot has moved and its latest command is zero."""
        with self.lock:
            return all(i in self.first_move_wall and self.last_cmd.get(i) == 0.0
                       for i in self.ids())

    def go_count(self):
        with self.lock:
            return len(self.go_msgs)

    def logged(self, text, node=None):
        with self.lock:
            return any(text == m and (node is None or node == name) for name, m in self.logs)


class NodeProcess(ChildProcess):
    """`rosrun multi_sync ARGS`, started at once: course_common's ChildProcess (its lines()
    as they come; stop() is Ctrl-C, then a kill); rosrun looks each executable up once
    (course_common.testing.rosrun_once)."""

    def __init__(self, *args, env=None):
        super().__init__(rosrun_once(['rosrun', 'multi_sync', *args]), env=env)
        self.start()

