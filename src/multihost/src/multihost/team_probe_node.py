"""team_probe: what a user on one host sees of the team, printed as JSON lines (tests, bench).

Run inside a host: python3 -m multihost.team_probe_node --robots robot_0 robot_1 [--status]
Every line is one event with the wall time it was received ("t", s; all hosts of this
machine share the clock):
    {"e": "ready"}                                        subscribed (the master answered)
    {"e": "pose", "r": NAME, "t", "x", "y"}               at most every --pose-period s
    {"e": "cmd", "r": NAME, "t", "v", "w"}                every command (linear.x, angular.z)
    {"e": "go", "t", "stamp"}                             a GO on team_status (--status)
    {"e": "status", "t", "id"}                            a robot's ready report (--status)
    {"e": "log", "t", "node", "level", "msg"}             /rosout_agg, warnings and worse
"""
import argparse
import json
import sys
import threading
import time

import rospy
from course_common.startup import init_node
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from turtlesim.msg import Pose

from multi_sync.msg import RobotStatus


class TeamProbe:
    """Subscribes to the robots' pose and cmd_vel (and team_status) and prints each event.

    Subscribes: <robot>/pose (Pose), <robot>/cmd_vel (Twist), team_status (RobotStatus, with
        --status), /rosout_agg (Log).
    Publishes: nothing. Services: none. Parameters: none (argv).
    """

    def __init__(self, robots, status, pose_period_s):
        self._lock = threading.Lock()
        self._pose_period_s = pose_period_s
        self._last_pose_t = {}
        self._subs = [rospy.Subscriber('/rosout_agg', Log, self._on_log, queue_size=100)]
        for robot in robots:
            self._subs.append(rospy.Subscriber('/%s/pose' % robot, Pose, self._on_pose, robot,
                                               queue_size=10, tcp_nodelay=True))
            self._subs.append(rospy.Subscriber('/%s/cmd_vel' % robot, Twist, self._on_cmd, robot,
                                               queue_size=100, tcp_nodelay=True))
        if status:
            self._subs.append(rospy.Subscriber('/team_status', RobotStatus, self._on_status,
                                               queue_size=100, tcp_nodelay=True))
        self.emit(e='ready')

    def emit(self, **event):
        line = json.dumps(event)
        with self._lock:
            sys.stdout.write(line + '\n')
            sys.stdout.flush()

    def _on_pose(self, msg, robot):
        now = time.time()
        if now - self._last_pose_t.get(robot, 0.0) >= self._pose_period_s:
            self._last_pose_t[robot] = now
            self.emit(e='pose', r=robot, t=now, x=msg.x, y=msg.y)

    def _on_cmd(self, msg, robot):
        self.emit(e='cmd', r=robot, t=time.time(), v=msg.linear.x, w=msg.angular.z)

    def _on_status(self, msg):
        now = time.time()
        if msg.header.frame_id == 'monitor':
            self.emit(e='go', t=now, stamp=msg.header.stamp.to_sec())
        elif msg.is_ready:
            self.emit(e='status', t=now, id=msg.robot_id)

    def _on_log(self, msg):
        if msg.level >= Log.WARN:
            self.emit(e='log', t=time.time(), node=msg.name, level=msg.level, msg=msg.msg)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--robots', nargs='+', required=True)
    parser.add_argument('--status', action='store_true', help='watch team_status too')
    parser.add_argument('--pose-period', type=float, default=0.1,
                        help='seconds between printed poses per robot (0: every pose)')
    args = parser.parse_args(rospy.myargv(argv if argv is not None else sys.argv)[1:])
    init_node('team_probe', disable_signals=False)
    TeamProbe(args.robots, args.status, args.pose_period)
    rospy.spin()


if __name__ == '__main__':
    main()
