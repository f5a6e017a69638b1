"""turtle_teleop_key: drive turtle1 with the arrow keys, as turtlesim's teleop does.

The node only: terminal reading, the publisher and main(). The key mapping is the pure
module teleop_keys, the raw terminal mode is terminal.
"""

import os
import select
import sys

import rospy
from course_common.param_loader import load_or_exit
from course_common.startup import init_node, quiet_at_shutdown
from geometry_msgs.msg import Twist

from turtle_lite.teleop_keys import (
    BANNER,
    DEFAULT_SCALE,
    TeleopConfig,
    is_quit_key,
    key_to_command,
)
from turtle_lite.terminal import RawTerminal

# How often the key loop looks at rospy.is_shutdown() while no key arrives, so that
# `rosnode kill` ends the node promptly even though it is waiting for a key.
SHUTDOWN_POLL_S = 0.1


class TeleopNode:
    """Publishes one Twist per arrow key press read from the terminal.

    Publishes:
        turtle1/cmd_vel (geometry_msgs/Twist, queue 1): linear.x = +/-scale_linear for
            up/down, angular.z = +/-scale_angular for left/right, all other fields 0.
            Nothing on key release and no auto-repeat: the turtle stops by the simulator's
            1 s command timeout, as with turtlesim.
    Parameters (read once, from the node namespace, not private, as turtlesim does):
        scale_linear (float, 2.0, m/s), scale_angular (float, 2.0, rad/s).
    """

    def __init__(self, config):
        self._config = config
        self._pub = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=1)

    def handle_key(self, key):
        """Publish the Twist for one byte; return False when the byte asks to quit."""
        if is_quit_key(key):
            return False
        command = key_to_command(key, self._config)
        if command is not None:
            twist = Twist()
            twist.linear.x, twist.angular.z = command
            self._pub.publish(twist)
        return True

    def run(self, fd):
        """Read keys from fd until 'q', end of input or ROS shutdown; return the exit code."""
        with RawTerminal(fd):
            for line in BANNER:  # after the mode switch, as turtlesim: no key gets echoed
                print(line)
            sys.stdout.flush()
            # A key pressed as ROS shuts down ends the loop quietly (None: not go on).
            handle_key = quiet_at_shutdown(self.handle_key)
            while not rospy.is_shutdown():
                ready, _, _ = select.select([fd], [], [], SHUTDOWN_POLL_S)
                if not ready:
                    continue
                try:
                    data = os.read(fd, 1)
                except OSError as err:  # EIO once the terminal has gone away
                    data, reason = b"", str(err)
                else:
                    reason = "end of input"
                if not data:
                    rospy.logerr("turtle_teleop_key: cannot read stdin (%s), quitting", reason)
                    return 1
                if not handle_key(data[0]):
                    return 0
        return 0


def load_config():
    """Read scale_linear/scale_angular from the node namespace into a TeleopConfig.

    Raises ParamError (a ValueError) naming a scale that is not a finite number.
    """
    values = {}
    for name in ("scale_linear", "scale_angular"):
        values[name] = rospy.get_param(name, DEFAULT_SCALE)
    return TeleopConfig(**values)


def main():
    fd = sys.stdin.fileno()
    if not os.isatty(fd):
        # Checked before init_node: there is no point registering a node that cannot read keys.
        sys.stderr.write(
            "turtle_teleop_key: stdin is not a terminal; it reads the arrow keys from one "
            "(under roslaunch, give the node launch-prefix=\"xterm -e\")\n"
        )
        sys.exit(1)
    init_node("teleop_turtle")
    config = load_or_exit(load_config, "turtle_teleop_key")
    rospy.loginfo(
        "teleop_turtle: scale_linear=%g m/s, scale_angular=%g rad/s",
        config.scale_linear,
        config.scale_angular,
    )
    node = TeleopNode(config)
    try:
        code = node.run(fd)
    except KeyboardInterrupt:  # SIGINT: the terminal is already restored by RawTerminal
        code = 0
    rospy.signal_shutdown("teleop finished")
    sys.exit(code)
