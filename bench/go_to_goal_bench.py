#!/usr/bin/env python3
"""Benchmark of Lab 2's go-to-goal law (./ws bench go_to_goal_bench): the lab's code as written
against closed_loop_turtle's move_turtle_to_goal.py, on the stand-in Pioneer.

Both drive the same fixed sequence of goals from the world's centre (each goal starts where
the previous one ended). Per goal: time from sending the goal to arrival, the final position
and heading errors once the robot has come to rest, how far it turned, how many poses it
spent against a wall, and the largest speeds it was commanded.

- lab_as_written: a line-for-line copy of the lab's move_turtle_to_goal.py callbacks, run in
  this process: the goal callback blocks in its own loop (publish, sleep 0.01 s) until
  "Reach position", then turns with the unwrapped beta = theta - theta_g until "Reach
  orientation"; no speed limit. Arrival = the callback returns.
- ours: the real node (rosrun closed_loop_turtle move_turtle_to_goal.py). Arrival = the goal
  on /pioneer/goal_reached.
The simulator is pioneer_mover's pioneer.launch (interface:=false) on its own master.
"""
import math
import os
import sys
import tempfile
import threading
import time

import numpy as np
import rospy
from course_common.angles import wrap_angle
from course_common.arena import SPAWN_M, WORLD_SIZE_M
from course_common.private_launch import POLL_S, PrivateMasterLaunch
from course_common.testing import WaitError, spawn, wait_for
from geometry_msgs.msg import Pose2D, Twist
from turtlesim.msg import Pose as TurtlePose
from turtlesim.srv import TeleportAbsolute

START = (SPAWN_M, SPAWN_M, 0.0)  # turtle1's spawn pose: the world's centre, heading +x
GOALS = (
    (8.5, 5.5, 0.0),    # ahead
    (2.5, 5.0, 3.0),    # behind the robot
    (2.5, 5.0, -3.0),   # same place, heading across the seam: 6.0 rad unwrapped, 0.28 wrapped
    (8.0, 8.5, 1.0),    # behind and to the right, far
    (1.0, 1.0, -1.5),   # far behind
)
WALL_EPS_M = 1e-3  # a pose this close to an edge is pinned against the wall
GOAL_TIMEOUT_S = 60.0  # the lab's loop has no way out: give up on a goal after this
START_TIMEOUT_S = 40.0
REST_TIMEOUT_S = 10.0
LAB_K_RHO, LAB_K_ALPHA, LAB_K_BETA = 3.14, 5, -3  # the lab's literals


class Watch:
    """The Pioneer's newest pose (Pose2D), turtlesim's velocities, turn and wall counters."""

    def __init__(self):
        self._lock = threading.Lock()
        self.pose = None
        self.turtle = None
        self._turned = 0.0
        self._wall = 0
        self._peak = (0.0, 0.0)
        rospy.Subscriber('/pioneer/pose', Pose2D, self._on_pose)
        rospy.Subscriber('/pioneer/cmd_vel', Twist, self._on_cmd)
        rospy.Subscriber('/pioneer/turtle_pose', TurtlePose, self._on_turtle)

    def _on_pose(self, msg):
        with self._lock:
            if self.pose is not None:
                self._turned += abs(wrap_angle(msg.theta - self.pose.theta))
            self.pose = msg
            if min(msg.x, msg.y) < WALL_EPS_M or max(msg.x, msg.y) > WORLD_SIZE_M - WALL_EPS_M:
                self._wall += 1

    def _on_cmd(self, msg):
        with self._lock:
            self._peak = (max(self._peak[0], abs(msg.linear.x)),
                          max(self._peak[1], abs(msg.angular.z)))

    def _on_turtle(self, msg):
        with self._lock:
            self.turtle = msg

    def reset_counters(self):
        with self._lock:
            self._turned, self._wall, self._peak = 0.0, 0, (0.0, 0.0)

    def counters(self):
        with self._lock:
            return self._turned, self._wall, self._peak

    def at_rest(self):
        with self._lock:
            return (self.turtle is not None and self.turtle.linear_velocity == 0.0
                    and self.turtle.angular_velocity == 0.0)


class LabAsWritten:
    """The lab's move_turtle_to_goal.py, callbacks copied as written (globals become fields).

    Only additions: a deadline so that a goal it never reaches ends the run, and print() kept
    out of the table's way.
    """

    def __init__(self, cmd_pub):
        self.velocity_pub = cmd_pub
        self.x_turtle = self.y_turtle = self.theta_turtle = None
        self.k_rho, self.k_alpha, self.k_beta = LAB_K_RHO, LAB_K_ALPHA, LAB_K_BETA
        rospy.Subscriber('/pioneer/pose', Pose2D, self.pose_recieved_callback)

    def pose_recieved_callback(self, turtle_pose):
        self.x_turtle = turtle_pose.x
        self.y_turtle = turtle_pose.y
        self.theta_turtle = turtle_pose.theta

    def goal_recieved_callback(self, turtle_goal, deadline):
        """Returns True at "Reach orientation", False if the deadline passed first."""
        x_g = turtle_goal.x
        y_g = turtle_goal.y
        theta_g = turtle_goal.theta
        rho = np.sqrt(np.power(x_g - self.x_turtle, 2) + np.power(y_g - self.y_turtle, 2))
        turtle_speed = Twist()
        while not rho < 0.1:
            rho = np.sqrt(np.power(x_g - self.x_turtle, 2) + np.power(y_g - self.y_turtle, 2))
            alpha = np.arctan2((y_g - self.y_turtle), (x_g - self.x_turtle)) - self.theta_turtle
            alpha = np.mod(alpha + np.pi, 2 * np.pi) - np.pi
            turtle_speed.linear.x = self.k_rho * rho
            turtle_speed.angular.z = (self.k_alpha * alpha)
            self.velocity_pub.publish(turtle_speed)
            rospy.sleep(0.01)
            if time.monotonic() > deadline:
                return False
        beta = self.theta_turtle - theta_g
        while not np.abs(beta) < 0.05:
            beta = self.theta_turtle - theta_g
            turtle_speed.linear.x = 0
            turtle_speed.angular.z = (self.k_beta * beta)
            self.velocity_pub.publish(turtle_speed)
            rospy.sleep(0.01)
            if time.monotonic() > deadline:
                return False
        turtle_speed.linear.x = 0
        turtle_speed.angular.z = 0
        self.velocity_pub.publish(turtle_speed)
        return True


def _teleport_to_start(cmd_pub, watch):
    cmd_pub.publish(Twist())
    rospy.ServiceProxy('/pioneer/teleport_absolute', TeleportAbsolute)(*START)
    wait_for(lambda: watch.pose is not None and abs(watch.pose.x - START[0]) < 1e-4
             and abs(watch.pose.theta - START[2]) < 1e-4 and watch.at_rest(),
             REST_TIMEOUT_S, 'the Pioneer back at the start, at rest', POLL_S)


def _result(watch, goal, sent_at, arrived_at):
    if arrived_at is None:
        turned, wall, peak = watch.counters()
        return {'time_s': None, 'pos_err_m': None, 'head_err_rad': None, 'turned_rad': turned,
                'wall_poses': wall, 'peak': peak}
    wait_for(watch.at_rest, REST_TIMEOUT_S, 'the Pioneer at rest after arriving', POLL_S)
    pose = watch.pose
    turned, wall, peak = watch.counters()
    return {'time_s': arrived_at - sent_at, 'peak': peak,
            'pos_err_m': math.hypot(pose.x - goal[0], pose.y - goal[1]),
            'head_err_rad': abs(wrap_angle(pose.theta - goal[2])), 'turned_rad': turned,
            'wall_poses': wall}


def run_lab(cmd_pub, watch):
    lab = LabAsWritten(cmd_pub)
    wait_for(lambda: lab.x_turtle is not None, START_TIMEOUT_S, 'the lab copy\'s first pose',
             POLL_S)
    _teleport_to_start(cmd_pub, watch)
    rows = []
    for goal in GOALS:
        watch.reset_counters()
        sent = time.monotonic()
        arrived = lab.goal_recieved_callback(Pose2D(*goal), sent + GOAL_TIMEOUT_S)
        rows.append(_result(watch, goal, sent, time.monotonic() if arrived else None))
        if not arrived:
            cmd_pub.publish(Twist())
            break  # where it is left is no start for the next goal
    return rows


def run_ours(cmd_pub, watch, log_dir):
    reached = []
    rospy.Subscriber('/pioneer/goal_reached', Pose2D,
                     lambda m: reached.append((time.monotonic(), (m.x, m.y, m.theta))))
    goal_pub = rospy.Publisher('/pioneer/goal', Pose2D, queue_size=10)
    node = spawn(['rosrun', 'closed_loop_turtle', 'move_turtle_to_goal.py',
                  '__name:=move_turtle_to_goal'],
                 log_path=os.path.join(log_dir, 'move_turtle_to_goal.log'))
    try:
        wait_for(lambda: goal_pub.get_num_connections() > 0, START_TIMEOUT_S,
                 'move_turtle_to_goal subscribed to /pioneer/goal', POLL_S)
        _teleport_to_start(cmd_pub, watch)
        rows = []
        for goal in GOALS:
            watch.reset_counters()
            count = len(reached)
            sent = time.monotonic()
            goal_pub.publish(Pose2D(*goal))
            try:
                wait_for(lambda g=goal, c=count: any(r[1] == g for r in reached[c:]),
                         GOAL_TIMEOUT_S, 'goal %r reached' % (goal,), POLL_S)
            except WaitError:
                rows.append(_result(watch, goal, sent, None))
                break
            arrived = next(r[0] for r in reached[count:] if r[1] == goal)
            rows.append(_result(watch, goal, sent, arrived))
        return rows
    finally:
        node.stop()


def _fmt(value, pattern):
    return 'not reached' if value is None else pattern % value


def main():
    out_dir = tempfile.mkdtemp(prefix='go_to_goal_bench_')
    started = time.monotonic()
    launch = PrivateMasterLaunch(['pioneer_mover', 'pioneer.launch', 'interface:=false'],
                                 os.path.join(out_dir, 'roslaunch.log'))
    try:
        launch.start()
        rospy.init_node('go_to_goal_bench', disable_signals=True)
        cmd_pub = rospy.Publisher('/pioneer/cmd_vel', Twist, queue_size=10)
        watch = Watch()
        wait_for(lambda: watch.pose is not None and cmd_pub.get_num_connections() > 0,
                 START_TIMEOUT_S, 'the stand-in Pioneer', POLL_S, alive=launch.alive)
        print('go_to_goal_bench: lab_as_written...', flush=True)
        lab_rows = run_lab(cmd_pub, watch)
        print('go_to_goal_bench: ours...', flush=True)
        our_rows = run_ours(cmd_pub, watch, out_dir)
    finally:
        rospy.signal_shutdown('bench done')
        launch.stop()
    print('\n| goal (x, y, theta) | lab as written: time (s) | final error (m / rad) | turned '
          '(rad) | poses at a wall | peak v (m/s) / w (rad/s) | ours: time (s) | final error '
          '(m / rad) | turned (rad) | poses at a wall | peak v / w |')
    print('|---|---|---|---|---|---|---|---|---|---|---|')
    for i, goal in enumerate(GOALS):
        cells = []
        for rows in (lab_rows, our_rows):
            row = rows[i] if i < len(rows) else None
            if row is None:
                cells += ['not run', '-', '-', '-', '-']
                continue
            error = ('-' if row['pos_err_m'] is None
                     else '%.3f / %.3f' % (row['pos_err_m'], row['head_err_rad']))
            cells += [_fmt(row['time_s'], '%.2f'), error, '%.2f' % row['turned_rad'],
                      '%d' % row['wall_poses'], '%.1f / %.1f' % row['peak']]
        print('| (%.1f, %.1f, %.1f) | ' % goal + ' | '.join(cells) + ' |')
    print('\ngo_to_goal_bench: done in %.0f s (logs in %s)' % (time.monotonic() - started,
                                                              out_dir))
    return 0


if __name__ == '__main__':
    sys.exit(main())
