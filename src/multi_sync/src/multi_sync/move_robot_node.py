"""The lesson's move_robot: announce ready, wait for the monitor's GO, drive forward safely."""
import sys
import threading
import time

import rospy
from course_common.command_line import parse_argv_or_exit
from course_common.param_loader import load_or_exit
from course_common.publishers import LostSubscribers, OnNewSubscriber, unqueued_publisher
from course_common.robot_ids import parse_robot_id
from course_common.startup import init_node, quiet_at_shutdown
from geometry_msgs.msg import Twist

from multi_sync.motion import TURTLESIM, Decision, TeamPositions, decide
from multi_sync.move_robot_params import drive_limits, load_config
from multi_sync.msg import RobotPosition, RobotStatus
from multi_sync.robot_sensors import RobotSensors
from multi_sync.team import MONITOR_FRAME_ID

# Deep enough for a 20-robot team's announcements and 10 Hz positions between two callbacks.
SHARED_QUEUE = 100


class MoveRobotNode:
    """One robot of the team: ready, wait for GO, then forward until a wall or teammate.

    The robot runs on turtlesim or on Stage, whichever publishes its pose
    (multi_sync.robot_sensors); move_robot_sync, the Stage lesson's executable, runs on Stage
    only (simulator=STAGE: no turtlesim topic, no square world). It is ready once it knows
    its pose and, on Stage, what its laser sees. It then publishes its ready status at once,
    again every announce_period_s until GO, and to every team_status subscriber that
    connects (so a monitor started or restarted at any time counts it). GO is any
    team_status message with header.frame_id "monitor": the first one starts the 10 Hz drive
    loop and sends the first command from the callback itself.

    Subscribes:
        robot_<id>/pose (turtlesim/Pose): the robot's pose on turtlesim; the bumper measures
            to the edge of turtlesim's square world.
        robot_<id>/base_pose_ground_truth (nav_msgs/Odometry): the robot's pose on Stage.
        robot_<id>/base_scan (sensor_msgs/LaserScan): the bumper on Stage: the nearest
            reading within cone_half_angle_rad of the heading.
        (Once the first pose names the simulator, the other one's topics are unsubscribed.)
        team_status (multi_sync/RobotStatus): GO from the monitor; teammates' reports ignored.
        team_positions (multi_sync/RobotPosition): teammates' positions (own ignored).
    Publishes:
        robot_<id>/cmd_vel (geometry_msgs/Twist): speed_mps forward at rate_hz after GO,
            0 when stopped by the bumper or a teammate, and 0 on shutdown.
        team_status (multi_sync/RobotStatus): ready status, robot_id = id, is_ready = true.
        A subscriber of cmd_vel, or before GO of team_status, that the master lists but
        that never connected gets the publisher registered again (WARN).
        team_positions (multi_sync/RobotPosition): own pose at rate_hz after GO.
    Services: none.
    Parameters (private):
        ~speed_mps (float, 0.2 m/s): forward speed, the lesson's 0.2.
        ~rate_hz (float, 10 Hz): drive loop rate, the lesson's 10.
        ~stop_distance_m (float, 0.5 m): the bumper stops the robot this far from the wall
            ahead (turtlesim: from the robot's centre; Stage: from its laser); 0 disables.
        ~min_gap_m (float, 1.0 m): stop while a teammate ahead is closer than this; 0 disables.
            Teammates' positions come from team_positions (Stage's lasers cannot see them).
        Both distances are bounded by the robot's simulator (move_robot_params): turtlesim's
        square, a laser's reach (100 m) on Stage. move_robot checks them when its first pose
        names the simulator: FATAL naming the parameter, and exit 1, when they do not fit.
        ~cone_half_angle_rad (float, 0.35 rad): Stage's bumper looks at the beams within this
            angle of the heading (0.35 rad covers the erratic's 0.35 m width at 0.5 m).
        ~input_timeout_s (float, 2.0 s of wall time): after GO, stop (and subscribe again
            every 5 s) while the pose or, on Stage, the scan has been silent this long: the
            bumper must not drive on what it saw seconds ago (a simulator that died, a
            network cut). 0 disables.
        ~world_size_m (float, 11.088889 m): side of the square world (turtlesim's; the bumper
            stays below half of it); no part on Stage, and not read by move_robot_sync.
        ~announce_period_s (float, 1.0 s): ready re-announcement period until GO.
        ~report_period_s (float, 5.0 s): how often the nearest teammate is logged.
    """

    def __init__(self, robot_id, config, simulator=None):
        self._id = robot_id
        self._cfg = config
        # How it drives: its simulator's limits, known at once (move_robot_sync) or from the
        # first pose (_on_ready).
        self._limits = drive_limits(config, simulator) if simulator is not None else None
        self.refused = False  # its parameters do not fit the simulator that answered
        self._team = TeamPositions(robot_id)
        self._lock = threading.Lock()
        self._go = False
        self._go_arrived_s = None  # time.monotonic() when GO arrived
        self._moved = False
        self._reason = None
        self._drive_timer = None
        self._stopped = False  # shutting down: no more commands but the final stop
        self._deferred = []  # log lines held back from the GO callback until the first tick
        self._sensors = RobotSensors(robot_id, config.cone_half_angle_rad, config.world_size_m,
                                     self._on_ready, simulator)
        # Synchronous: the first command leaves within the GO callback, the final stop
        # before the process exits.
        self._cmd_pub = unqueued_publisher('robot_%d/cmd_vel' % robot_id, Twist)
        # A simulator that missed this publisher would never move the robot (team20, once).
        self._cmd_lost = LostSubscribers(self._cmd_pub, describe='Robot %d: %%s' % robot_id)
        self._pos_pub = rospy.Publisher('team_positions', RobotPosition, queue_size=10)
        self._status_pub = rospy.Publisher('team_status', RobotStatus, queue_size=10,
                                           subscriber_listener=OnNewSubscriber(self.announce_to))
        # A monitor that missed this publisher would never hear the robot ready: no GO.
        self._status_lost = LostSubscribers(self._status_pub,
                                            describe='Robot %d: %%s' % robot_id)
        rospy.on_shutdown(self._stop)
        # reset=True: on sim time a restarted stageros sends /clock back to its start, which
        # would end a plain rospy.Timer (ROSTimeMovedBackwardsException).
        self._announce_timer = rospy.Timer(rospy.Duration(config.announce_period_s),
                                           quiet_at_shutdown(self._on_announce_timer),
                                           reset=True)
        self._sensors.subscribe()
        rospy.Subscriber('team_positions', RobotPosition, self._on_position,
                         queue_size=SHARED_QUEUE)
        # tcp_nodelay: GO is one small message; Nagle's algorithm could hold it back.
        rospy.Subscriber('team_status', RobotStatus, self._on_status, queue_size=SHARED_QUEUE,
                         tcp_nodelay=True)

    # --- readiness -------------------------------------------------------------------------
    def _ready_msg(self):
        msg = RobotStatus()
        msg.header.stamp = rospy.Time.now()
        msg.robot_id = self._id
        msg.is_ready = True
        return msg

    def announce_to(self, send):
        """Send the ready status with send (a publish function) if the robot is ready."""
        if self._ready():
            send(self._ready_msg())

    def _ready(self):
        """It knows where it is and what is ahead, and drives by its simulator's limits."""
        with self._lock:
            known = self._limits is not None
        return known and self._sensors.fix() is not None

    def _on_ready(self):
        if not self._take_limits():
            return
        with self._lock:
            go = self._go
        if not go:
            self._status_pub.publish(self._ready_msg())
            rospy.loginfo('Robot %d published ready status', self._id)

    def _take_limits(self):
        """The limits of the simulator the first pose named (move_robot), once; False when
        the parameters do not fit it: FATAL naming them, and the node shuts down (exit 1)."""
        with self._lock:
            if self._limits is not None:
                return True
        simulator = self._sensors.simulator()
        try:
            limits = drive_limits(self._cfg, simulator)
        except ValueError as err:
            rospy.logfatal('move_robot: %s (on %s)', err, simulator)
            self.refused = True
            rospy.signal_shutdown('parameters that do not fit %s' % simulator)
            return False
        with self._lock:
            self._limits = limits
        return True

    def _on_announce_timer(self, _event):
        with self._lock:
            go = self._go
        if go:
            return
        self._cmd_lost.check()
        self._status_lost.check()
        missing = self._sensors.missing()
        if missing:
            rospy.logwarn_throttle(5.0, 'Robot %d: %s' % (self._id, missing))
            self._sensors.resubscribe_if_silent(self._cfg.input_timeout_s)
            return
        if not self._ready():  # its limits are being taken, or refused
            return
        self._status_pub.publish(self._ready_msg())
        rospy.loginfo('Robot %d: waiting for team', self._id)

    def _on_status(self, msg):
        if msg.header.frame_id != MONITOR_FRAME_ID:
            return
        with self._lock:
            if self._go or self._stopped:
                return
            self._go = True
            self._go_arrived_s = time.monotonic()
            # Event-driven start: the first command leaves from this callback. Everything
            # else (log lines, sharing the position) waits for the first tick, so that a
            # whole team starting at once does not hold each other's first commands up.
            self._deferred.append("Robot %d: Team is ready. Let's move!" % self._id)
            self._deferred.extend(self._command_locked())
            self._drive_timer = rospy.Timer(rospy.Duration(1.0 / self._cfg.rate_hz),
                                            quiet_at_shutdown(self._on_tick), reset=True)
        self._announce_timer.shutdown()

    # --- driving ---------------------------------------------------------------------------
    def _on_tick(self, _event):
        with self._lock:
            logs, self._deferred = self._deferred, []
            logs.extend(self._command_locked())
            logs.extend(self._share_locked())
        self._log(logs)
        # Outside the lock: these talk to the master.
        self._sensors.resubscribe_if_silent(self._cfg.input_timeout_s)
        self._cmd_lost.check()

    def _command_locked(self):
        """Command the robot from its latest fix; return the log lines for after the lock."""
        fix = self._sensors.fix()
        if fix is None or self._limits is None or self._stopped:
            return []
        stale = self._sensors.stale(self._cfg.input_timeout_s) \
            if self._cfg.input_timeout_s > 0.0 else ''
        if stale:
            decision = Decision(0.0, 'stale', fix.ahead_m)
        else:
            decision = decide(fix.x, fix.y, fix.theta, fix.ahead_m, self._limits, self._team)
        cmd = Twist()
        cmd.linear.x = decision.linear_mps
        self._cmd_pub.publish(cmd)
        logs = []
        if decision.linear_mps > 0.0 and not self._moved:
            self._moved = True
            logs.append(self._first_move_line())
        if decision.reason != self._reason:
            if decision.reason == 'wall':
                what = 'wall' if self._sensors.simulator() == TURTLESIM else 'laser: obstacle'
                logs.append('Robot %d: %s %.2f m ahead, stopping'
                            % (self._id, what, decision.ahead_m))
            elif decision.reason == 'stale':
                logs.append('Robot %d: %s, stopping' % (self._id, stale))
            elif decision.reason == 'teammate':
                logs.append('Robot %d: robot %d is %.2f m ahead, waiting'
                            % (self._id, decision.teammate_id, decision.gap_m))
            elif self._reason is not None:
                logs.append('Robot %d: path clear, moving on' % self._id)
            self._reason = decision.reason
        return logs

    def _first_move_line(self):
        """How long after GO's arrival the first move command left, on this robot's clock.

        From the arrival, not from GO's stamp: the monitor stamps GO on its own clock (sim
        time on Stage, in 0.1 s steps; wall time on turtlesim, on another host perhaps).
        """
        return 'Robot %d: first move command %.1f ms after GO arrived' % (
            self._id, (time.monotonic() - self._go_arrived_s) * 1e3)

    def _share_locked(self):
        """Publish the robot's position for its teammates; return the nearest-teammate log."""
        fix = self._sensors.fix()
        if fix is None:
            return []
        x, y, theta = fix.x, fix.y, fix.theta
        position = RobotPosition()
        position.header.stamp = rospy.Time.now()
        position.header.frame_id = 'world'
        position.robot_id = self._id
        position.pose.x, position.pose.y, position.pose.theta = x, y, theta
        self._pos_pub.publish(position)
        nearest = self._team.nearest(x, y)
        if nearest is None:
            return []
        return [('throttle', 'Robot %d: nearest teammate is robot %d, %.2f m away'
                 % (self._id, nearest[0].robot_id, nearest[1]))]

    def _log(self, logs):
        for line in logs:
            if isinstance(line, tuple):
                rospy.loginfo_throttle(self._cfg.report_period_s, line[1])
            else:
                rospy.loginfo(line)

    def _on_position(self, msg):
        try:
            with self._lock:
                self._team.update(msg.robot_id, msg.pose.x, msg.pose.y, msg.pose.theta,
                                  msg.header.stamp.to_sec())
        except ValueError as err:
            rospy.logwarn_throttle(5.0, 'Robot %d: ignoring teammate position: %s'
                                   % (self._id, err))

    def _stop(self):
        # Under the lock, so that no tick can send a non-zero command after the stop.
        with self._lock:
            self._stopped = True
            if self._drive_timer is not None:
                self._drive_timer.shutdown()
            self._cmd_pub.publish(Twist())


def main(argv=None, simulator=None):
    """rosrun multi_sync move_robot ROBOT_ID (either simulator), or move_robot_sync ROBOT_ID
    (the Stage lesson's: simulator=STAGE)."""
    robot_id = parse_argv_or_exit(parse_robot_id, argv)
    init_node('move_robot_%d' % robot_id)
    config = load_or_exit(lambda: load_config(rospy.get_param, simulator), 'move_robot')
    rospy.loginfo('Robot %d: %s', robot_id, config)
    node = MoveRobotNode(robot_id, config, simulator)
    rospy.spin()
    if node.refused:
        sys.exit(1)
