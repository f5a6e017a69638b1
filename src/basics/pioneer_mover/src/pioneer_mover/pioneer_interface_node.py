"""ROS node of Lab 2 task one: the teleop's command at a quarter speed for the Pioneer."""
import contextlib
from dataclasses import dataclass

import rospy
from course_common.param_loader import get_private, load_or_exit
from course_common.params import check_number
from geometry_msgs.msg import Twist

from pioneer_mover.relay import DEFAULT_DIVISOR, check_divisor, scale_twist

QUEUE_SIZE = 10  # the lab's publisher queue
WARN_PERIOD_S = 5.0  # throttle for repeated bad-input warnings


@dataclass(frozen=True)
class InterfaceConfig:
    """pioneer_interface's parameters, validated."""

    divisor: float


def load_config():
    """Reads and validates ~divisor. Raises ParamError (a ValueError) naming the parameter."""
    value = check_number('~divisor', get_private('divisor', DEFAULT_DIVISOR), low=0.0,
                         low_open=True)
    return InterfaceConfig(divisor=check_divisor(value))


def _components(twist):
    return (twist.linear.x, twist.linear.y, twist.linear.z,
            twist.angular.x, twist.angular.y, twist.angular.z)


def _twist(values):
    twist = Twist()
    (twist.linear.x, twist.linear.y, twist.linear.z,
     twist.angular.x, twist.angular.y, twist.angular.z) = values
    return twist


class PioneerInterfaceNode:
    """Republishes each teleop command, divided by 4, to the Pioneer (Lab 2, task one).

    Logs the lab's line "The robot velocity is (v, w)" for every command received.
    A command with a NaN or infinite component is dropped with a throttled warning.

    Subscribes:
        /turtle1/cmd_vel (geometry_msgs/Twist): the teleop's command (the lab's name).
    Publishes:
        /pioneer/cmd_vel (geometry_msgs/Twist, queue 10): the command divided by ~divisor.
    Services: none.
    Parameters:
        ~divisor (float, default 4.0, > 0): what every component is divided by.
    The two names are the lab's absolute ones; remaps apply.
    """

    def __init__(self, config):
        self._config = config
        self._pub = rospy.Publisher('/pioneer/cmd_vel', Twist, queue_size=QUEUE_SIZE)
        # Subscribe last: the callback publishes.
        self._sub = rospy.Subscriber('/turtle1/cmd_vel', Twist, self._on_velocity)

    def _on_velocity(self, robot_velocity):
        # The lab's line and formatting (Python's str of each float: "(2.0, -1.2)").
        rospy.loginfo(f'The robot velocity is ({robot_velocity.linear.x}, '
                      f'{robot_velocity.angular.z})')
        try:
            scaled = scale_twist(_components(robot_velocity), self._config.divisor)
        except ValueError as err:
            rospy.logwarn_throttle(WARN_PERIOD_S, 'pioneer_interface: not forwarding %s; '
                                   'expected finite numbers' % err)
            return
        with contextlib.suppress(rospy.ROSException, ValueError):
            # A command racing shutdown finds the publisher closed: nothing left to drive.
            self._pub.publish(_twist(scaled))


def main():
    """Entry point of pioneer_interface.py."""
    # anonymous=True as in the lab: two copies can run side by side.
    rospy.init_node('pioneer_interface', anonymous=True)
    config = load_or_exit(load_config, 'pioneer_interface')
    rospy.loginfo('pioneer_interface: %s -> %s divided by %g',
                  rospy.resolve_name('/turtle1/cmd_vel'), rospy.resolve_name('/pioneer/cmd_vel'),
                  config.divisor)
    PioneerInterfaceNode(config)
    rospy.spin()
