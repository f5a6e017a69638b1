"""team_probe: what a user on one host sees of the team, printed as JSON lines (tests, bench).

Run inside a host: python3 -m multihost.team_probe_node --robots robot_0 robot_1 [--status]
[--stage]. Every line is one event with the wall time it was received ("t", s; all hosts of
this machine share the clock):
    {"e": "ready"}                                        subscribed (the master answered)
    {"e": "pose", "r": NAME, "t", "x", "y", "v"}          at most every --pose-period s
        v: the forward speed the simulator is applying (m/s): turtlesim's Pose.linear_velocity
        (0 once its 1 s command timeout ran out); on Stage (--stage) the odom twist of the
        same step, the command Stage keeps (non-zero while the robot is stalled). A pose
        that stays put while v is not 0 is a robot stalled against something.
        With --stage also "st": the step's sim time (s), and x, y from the ground truth.
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
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from turtlesim.msg import Pose

from multi_sync.msg import RobotStatus
from multihost.step_pairs import StepPairs


class TeamProbe:
    """Subscribes to the robots' poses and cmd_vel (and team_status) and prints each event.

    Subscribes: <robot>/pose (turtlesim/Pose), or with --stage <robot>/base_pose_ground_truth
        and <robot>/odom (nav_msgs/Odometry, paired by stamp); <robot>/cmd_vel (Twist),
        team_status (RobotStatus, with --status), /rosout_agg (Log).
    Publishes: nothing. Services: none. Parameters: none (argv).
    """

    def __init__(self, robots, status, pose_period_s, stage=False):
        self._lock = threading.Lock()
        self._pose_period_s = pose_period_s
        self._last_pose_t = {}
        self._steps = StepPairs(('x', 'y', 'v'))  # Stage: ground truth + odom of a step
        self._subs = [rospy.Subscriber('/rosout_agg', Log, self._on_log, queue_size=100)]
        for robot in robots:
            if stage:
                self._subs += [
                    rospy.Subscriber('/%s/base_pose_ground_truth' % robot, Odometry,
                                     self._on_ground_truth, robot, queue_size=10,
                                     tcp_nodelay=True),
                    rospy.Subscriber('/%s/odom' % robot, Odometry, self._on_odom, robot,
                                     queue_size=10, tcp_nodelay=True)]
            else:
                self._subs.append(rospy.Subscriber('/%s/pose' % robot, Pose, self._on_pose,
                                                   robot, queue_size=10, tcp_nodelay=True))
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
        self._pose(robot, x=msg.x, y=msg.y, v=msg.linear_velocity)

    def _on_ground_truth(self, msg, robot):
        p = msg.pose.pose.position
        self._stage_half(robot, msg.header.stamp, x=p.x, y=p.y)

    def _on_odom(self, msg, robot):
        self._stage_half(robot, msg.header.stamp, v=msg.twist.twist.linear.x)

    def _stage_half(self, robot, stamp, **half):
        """One pose event once both halves of a Stage step (same stamp) are here."""
        with self._lock:
            whole = self._steps.add(robot, stamp.to_nsec(), **half)
        if whole is not None:
            self._pose(robot, st=stamp.to_sec(), **whole)

    def _pose(self, robot, **pose):
        now = time.time()
        with self._lock:
            if now - self._last_pose_t.get(robot, 0.0) < self._pose_period_s:
                return
            self._last_pose_t[robot] = now
        self.emit(e='pose', r=robot, t=now, **pose)

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
    parser.add_argument('--stage', action='store_true',
                        help="Stage's robots: poses from base_pose_ground_truth and odom")
    args = parser.parse_args(rospy.myargv(argv if argv is not None else sys.argv)[1:])
    init_node('team_probe', disable_signals=False)
    TeamProbe(args.robots, args.status, args.pose_period, args.stage)
    rospy.spin()


if __name__ == '__main__':
    main()
