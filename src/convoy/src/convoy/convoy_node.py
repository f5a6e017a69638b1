"""ROS node of the convoy practice: one follower turtle chasing its leader (convoy_node)."""
import threading
from dataclasses import dataclass

import rospy
from course_common.param_loader import get_private, load_or_exit
from course_common.params import check_number, check_text
from turtlesim.msg import Pose

from convoy.control import (
    DEFAULT_KP_AV,
    DEFAULT_KP_LV,
    DEFAULT_TOLERANCE_M,
    Gains,
    follow,
    is_finite_pose,
)
from convoy.ros_io import CommandPublisher, pose_from_msg

QUEUE_SIZE = 10  # the course's queue for both subscriptions and the command publisher
WARN_PERIOD_S = 5.0  # throttle for repeated bad-input warnings


@dataclass(frozen=True)
class ConvoyConfig:
    """convoy_node's parameters, validated."""

    leader_pose: str
    follower_pose: str
    follower_speeds: str
    gains: Gains


def _topic_param(name):
    return check_text('~' + name, get_private(name), 'a non-empty topic name, e.g. /robot2/pose')


def _gain_param(name, default):
    return check_number('~' + name, get_private(name, default), low=0.0)


def load_config():
    """Reads and validates the private parameters. Raises ParamError (a ValueError)."""
    return ConvoyConfig(
        leader_pose=_topic_param('leader_pose'),
        follower_pose=_topic_param('follower_pose'),
        follower_speeds=_topic_param('follower_speeds'),
        gains=Gains(kp_lv=_gain_param('kp_lv', DEFAULT_KP_LV),
                    kp_av=_gain_param('kp_av', DEFAULT_KP_AV),
                    tolerance_m=_gain_param('distance_tolerance', DEFAULT_TOLERANCE_M)))


class ConvoyNode:
    """Follower of the convoy practice: steers one turtle towards its leader.

    The course's control law (convoy.control.follow), with the heading error wrapped into
    [-pi, pi) so the follower always turns the short way (the course does not wrap it).
    A command is computed and published on every follower pose (the pose rate, 62.5 Hz with
    turtlesim), and only once both poses have been received (the course starts from a zero
    leader pose). Poses with NaN or infinite fields are ignored with a throttled warning.

    Subscribes:
        ~leader_pose (turtlesim/Pose, queue 10): the leader's pose.
        ~follower_pose (turtlesim/Pose, queue 10): the follower's pose; triggers a command.
    Publishes:
        ~follower_speeds (geometry_msgs/Twist, queue 10): the follower's command; a zero Twist
            inside the tolerance and once at shutdown.
    Services: none.
    Parameters:
        ~leader_pose (str, required): topic of the leader's pose, e.g. /robot1/pose.
        ~follower_pose (str, required): topic of the follower's pose, e.g. /robot2/pose.
        ~follower_speeds (str, required): topic of the follower's command, e.g. /robot2/cmd_vel.
        ~kp_lv (float, default 0.3, 1/s): forward speed per metre of distance (course Kp_lv).
        ~kp_av (float, default 1.35, 1/s): turn rate per radian of heading error (course Kp_av).
        ~distance_tolerance (float, default 1.5, m): the follower stops closer than this.
    The three topic names resolve like any rospy name: relative ones in the node's namespace,
    and launch-file remaps apply.
    """

    def __init__(self, config):
        self._config = config
        self._lock = threading.Lock()
        self._leader = None
        self._follower = None
        self._commands = CommandPublisher(config.follower_speeds, QUEUE_SIZE)
        # Subscribe last: the callbacks use the publisher and the lock.
        self._follower_sub = rospy.Subscriber(config.follower_pose, Pose, self._on_follower,
                                              queue_size=QUEUE_SIZE)
        self._leader_sub = rospy.Subscriber(config.leader_pose, Pose, self._on_leader,
                                            queue_size=QUEUE_SIZE)

    @staticmethod
    def _checked(msg, which):
        pose = pose_from_msg(msg)
        if not is_finite_pose(pose):
            rospy.logwarn_throttle(WARN_PERIOD_S, 'convoy: ignoring a %s pose with non-finite '
                                   'fields (x=%r, y=%r, theta=%r): expected finite numbers'
                                   % (which, pose.x, pose.y, pose.theta))
            return None
        return pose

    def _on_leader(self, msg):
        pose = self._checked(msg, 'leader')
        if pose is not None:
            with self._lock:
                self._leader = pose

    def _on_follower(self, msg):
        pose = self._checked(msg, 'follower')
        if pose is None:
            return
        with self._lock:
            self._follower = pose
            leader = self._leader
        if leader is None:
            return  # no command until both poses are known
        self._commands.publish(follow(leader, pose, self._config.gains))

    def stop(self):
        """Sends one zero Twist (called at shutdown)."""
        self._commands.stop()


def main():
    """Entry point of convoy_node."""
    rospy.init_node('convoy_node')
    config = load_or_exit(load_config, 'convoy_node')
    rospy.loginfo('convoy_node: leader_pose=%s follower_pose=%s follower_speeds=%s kp_lv=%g '
                  'kp_av=%g distance_tolerance=%g m',
                  rospy.resolve_name(config.leader_pose), rospy.resolve_name(config.follower_pose),
                  rospy.resolve_name(config.follower_speeds), config.gains.kp_lv,
                  config.gains.kp_av, config.gains.tolerance_m)
    node = ConvoyNode(config)
    rospy.on_shutdown(node.stop)
    rospy.spin()
