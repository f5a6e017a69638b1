"""ROS node that drives the convoy's leader along a figure eight, so nobody needs the keyboard."""
import threading
from dataclasses import dataclass

import rospy
from course_common.param_loader import get_private, load_or_exit
from course_common.params import check_number
from turtlesim.msg import Pose

from convoy.control import is_finite_pose
from convoy.path import (
    DEFAULT_HALF_HEIGHT_M,
    DEFAULT_HALF_WIDTH_M,
    DEFAULT_LOOKAHEAD_M,
    DEFAULT_MAX_TURN_RADPS,
    DEFAULT_SPEED_MPS,
    WORLD_CENTRE_M,
    Lemniscate,
    PurePursuit,
)
from convoy.ros_io import CommandPublisher, pose_from_msg

WARN_PERIOD_S = 5.0  # throttle for repeated bad-input warnings
# The path must keep this far from the walls: the followers cut inside the leader's curves,
# and a turtle pushing on a wall floods the console with turtlesim's clamping warning.
WALL_MARGIN_M = 0.5


@dataclass(frozen=True)
class AutopilotConfig:
    """The autopilot's parameters, validated."""

    path: Lemniscate
    speed_mps: float
    lookahead_m: float
    max_turn_radps: float


def _number_param(name, default):
    return check_number('~' + name, get_private(name, default), low=0.0, low_open=True)


def load_config():
    """Reads and validates the private parameters. Raises ParamError or ValueError."""
    path = Lemniscate(centre_x=_number_param('centre_x', WORLD_CENTRE_M),
                      centre_y=_number_param('centre_y', WORLD_CENTRE_M),
                      half_width=_number_param('half_width', DEFAULT_HALF_WIDTH_M),
                      half_height=_number_param('half_height', DEFAULT_HALF_HEIGHT_M))
    if not path.fits_in_world(WALL_MARGIN_M):
        raise ValueError('parameters ~centre_x/~centre_y/~half_width/~half_height give a path '
                          'with bounds %r: expected it %.1f m inside the walls of the %.2f m world'
                          % (tuple(round(b, 2) for b in path.bounds()), WALL_MARGIN_M,
                             2.0 * WORLD_CENTRE_M))
    return AutopilotConfig(path=path,
                           speed_mps=_number_param('speed', DEFAULT_SPEED_MPS),
                           lookahead_m=_number_param('lookahead', DEFAULT_LOOKAHEAD_M),
                           max_turn_radps=_number_param('max_turn', DEFAULT_MAX_TURN_RADPS))


class AutopilotNode:
    """Drives one turtle along a figure eight (pure pursuit), a command on every pose.

    Subscribes:
        pose (turtlesim/Pose, queue 1): the turtle's pose; remap to e.g. /robot1/pose.
    Publishes:
        cmd_vel (geometry_msgs/Twist, queue 1): the turtle's command; remap to /robot1/cmd_vel.
            A zero Twist at shutdown.
    Services: none.
    Parameters:
        ~centre_x, ~centre_y (float, default 5.544445, m): centre of the eight (the world's).
        ~half_width (float, default 4.5, m): half the eight's width (along x).
        ~half_height (float, default 4.0, m): half the eight's height (along y).
        ~speed (float, default 0.5, m/s): forward speed.
        ~lookahead (float, default 0.8, m): pure-pursuit lookahead distance.
        ~max_turn (float, default 2.0, rad/s): largest turn rate commanded.
    """

    def __init__(self, config):
        self._lock = threading.Lock()
        self._pursuit = PurePursuit(config.path, config.speed_mps, config.lookahead_m,
                                    config.max_turn_radps)
        self._commands = CommandPublisher('cmd_vel', 1)
        self._sub = rospy.Subscriber('pose', Pose, self._on_pose, queue_size=1)

    def _on_pose(self, msg):
        pose = pose_from_msg(msg)
        if not is_finite_pose(pose):
            rospy.logwarn_throttle(WARN_PERIOD_S, 'autopilot: ignoring a pose with non-finite '
                                   'fields (x=%r, y=%r, theta=%r)' % (pose.x, pose.y, pose.theta))
            return
        with self._lock:
            command = self._pursuit.command(pose)
        self._commands.publish(command)

    def stop(self):
        """Sends one zero Twist (called at shutdown)."""
        self._commands.stop()


def main():
    """Entry point of autopilot."""
    rospy.init_node('autopilot')
    config = load_or_exit(load_config, 'autopilot')
    rospy.loginfo('autopilot: figure eight centred at (%.2f, %.2f) m, %.2f x %.2f m, at %.2f m/s, '
                  'driving %s from %s', config.path.centre_x, config.path.centre_y,
                  2 * config.path.half_width, 2 * config.path.half_height, config.speed_mps,
                  rospy.resolve_name('cmd_vel'), rospy.resolve_name('pose'))
    node = AutopilotNode(config)
    rospy.on_shutdown(node.stop)
    rospy.spin()
