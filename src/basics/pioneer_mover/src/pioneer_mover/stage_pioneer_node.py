"""ROS node standing in for the lab's CoppeliaSim script on Stage's Pioneer 3-DX: the lab's
wheel speeds in, the Stage robot's velocity out, its true pose back as Pose2D."""
import contextlib
import math
from dataclasses import dataclass

import rospy
from course_common.angles import yaw_from_quaternion
from course_common.finite import is_finite_number
from course_common.param_loader import get_private, load_or_exit
from course_common.params import check_number
from course_common.startup import init_node
from geometry_msgs.msg import Pose2D, Twist
from nav_msgs.msg import Odometry

from pioneer_mover.relay import pose2d_fields
from pioneer_mover.wheels import TRACK_WIDTH_M, WheelLimits, drive

COMMAND_QUEUE = 10  # the lab's queue for commands
POSE_QUEUE = 1  # only the newest pose matters to a controller
WARN_PERIOD_S = 5.0  # throttle for repeated bad-input warnings
CLAMP_LOG_PERIOD_S = 5.0  # throttle for the "held within limits" line (go-to-goal asks 100/s)


@dataclass(frozen=True)
class StagePioneerConfig:
    """stage_pioneer's parameters, validated."""

    track_m: float
    limits: WheelLimits


def load_config():
    """Reads and validates the private parameters. Raises ParamError naming the parameter."""
    defaults = WheelLimits()

    def positive(name, default):
        return check_number('~' + name, get_private(name, default), low=0.0, low_open=True)

    return StagePioneerConfig(
        track_m=positive('track_width_m', TRACK_WIDTH_M),
        limits=WheelLimits(positive('max_wheel_mps', defaults.max_wheel_mps),
                           positive('max_turn_radps', defaults.max_turn_radps)))


def _components(twist):
    return (twist.linear.x, twist.linear.y, twist.linear.z,
            twist.angular.x, twist.angular.y, twist.angular.z)


class StagePioneerNode:
    """What the lab's CoppeliaSim script does, for Stage's Pioneer 3-DX.

    Each command becomes the lab's wheel speeds vLeft = v - (L/2) w, vRight = v + (L/2) w;
    both are scaled by one factor so that no wheel exceeds ~max_wheel_mps and the turn does
    not exceed ~max_turn_radps (a throttled INFO says when), and the wheels go to Stage as
    the body velocity they make. A command with a NaN or infinite component is refused
    (throttled WARN) and nothing is sent: Stage keeps the last good command until its
    watchdog stops it. Each ground-truth pose of the Stage robot goes out as Pose2D, as the
    lab's script publishes the robot's world pose.

    Subscribes:
        cmd_vel (geometry_msgs/Twist, queue 10): the lab's command (linear.x, angular.z).
        stage/base_pose_ground_truth (nav_msgs/Odometry, queue 1): stageros's world pose.
    Publishes:
        stage/cmd_vel (geometry_msgs/Twist, queue 10): the Stage robot's velocity.
        pose (geometry_msgs/Pose2D, queue 1): x, y in metres, theta in radians, 10 Hz of
            simulated time (one per Stage step).
    Services: none.
    Parameters:
        ~track_width_m (float, default 0.33 m, > 0): the lab's L.
        ~max_wheel_mps (float, default 0.5 m/s, > 0): a wheel's top speed.
        ~max_turn_radps (float, default 1.5708 rad/s = 90 deg/s, > 0): the top turn rate.
    Names are relative: pioneer.launch starts the node in /pioneer, stageros in /pioneer/stage.
    """

    def __init__(self, config):
        self._config = config
        self._cmd_pub = rospy.Publisher('stage/cmd_vel', Twist, queue_size=COMMAND_QUEUE)
        self._pose_pub = rospy.Publisher('pose', Pose2D, queue_size=POSE_QUEUE)
        # Subscribe last: the callbacks publish.
        self._pose_sub = rospy.Subscriber('stage/base_pose_ground_truth', Odometry,
                                          self._on_pose, queue_size=POSE_QUEUE)
        self._cmd_sub = rospy.Subscriber('cmd_vel', Twist, self._on_command,
                                         queue_size=COMMAND_QUEUE)

    def _on_command(self, msg):
        values = _components(msg)
        if not all(is_finite_number(v) for v in values):
            rospy.logwarn_throttle(WARN_PERIOD_S, 'stage_pioneer: refusing command (linear '
                                   '%r, %r, %r; angular %r, %r, %r): expected finite numbers; '
                                   'nothing sent to the robot' % values)
            return
        limits = self._config.limits
        result = drive(msg.linear.x, msg.angular.z, limits, self._config.track_m)
        if result.limited:
            rospy.loginfo_throttle(
                CLAMP_LOG_PERIOD_S, 'stage_pioneer: wheels (%.3f, %.3f) m/s held to (%.3f, '
                '%.3f) m/s: at most %.3f m/s a wheel and %.3f rad/s of turn'
                % (result.asked_mps + result.wheels_mps
                   + (limits.max_wheel_mps, limits.max_turn_radps)))
        twist = Twist()
        twist.linear.x, twist.angular.z = result.linear_mps, result.angular_radps
        with contextlib.suppress(rospy.ROSException, ValueError):
            # A command racing shutdown finds the publisher closed: nothing left to drive.
            self._cmd_pub.publish(twist)

    def _on_pose(self, msg):
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        try:
            yaw = yaw_from_quaternion(q.x, q.y, q.z, q.w)
            x, y, theta = pose2d_fields(p.x, p.y, yaw)
        except ValueError as err:
            rospy.logwarn_throttle(WARN_PERIOD_S, 'stage_pioneer: dropping pose: %s' % err)
            return
        with contextlib.suppress(rospy.ROSException, ValueError):
            self._pose_pub.publish(Pose2D(x=x, y=y, theta=theta))


def main():
    """Entry point of stage_pioneer."""
    init_node('stage_pioneer')
    config = load_or_exit(load_config, 'stage_pioneer')
    rospy.loginfo('stage_pioneer: %s -> wheels (L = %g m, at most %g m/s a wheel, %g rad/s '
                  '= %g deg/s of turn) -> %s; %s -> %s (Pose2D)',
                  rospy.resolve_name('cmd_vel'), config.track_m, config.limits.max_wheel_mps,
                  config.limits.max_turn_radps, math.degrees(config.limits.max_turn_radps),
                  rospy.resolve_name('stage/cmd_vel'),
                  rospy.resolve_name('stage/base_pose_ground_truth'), rospy.resolve_name('pose'))
    StagePioneerNode(config)
    rospy.spin()
