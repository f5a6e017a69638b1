"""turtle_teleop_key: drive turtle1 with the arrow keys, as turtlesim's teleop does.

The top half is the pure key mapping (no ROS, unit-tested); the bottom half is the node:
terminal handling, the publisher and main().
"""

import math
import os
import select
import sys
import termios
from dataclasses import dataclass

import rospy
from geometry_msgs.msg import Twist

# Only the last byte of an arrow escape sequence (ESC [ A) matters, exactly as in turtlesim,
# so a plain uppercase A-D also drives the turtle.
KEY_UP = 0x41  # 'A'
KEY_DOWN = 0x42  # 'B'
KEY_RIGHT = 0x43  # 'C'
KEY_LEFT = 0x44  # 'D'
KEY_QUIT = 0x71  # 'q'

DEFAULT_SCALE = 2.0  # turtlesim's default for both scale_linear and scale_angular

# The three lines turtlesim prints before reading keys (kept verbatim).
BANNER = (
    "Reading from keyboard",
    "---------------------------",
    "Use arrow keys to move the turtle. 'q' to quit.",
)

# How often the key loop looks at rospy.is_shutdown() while no key arrives, so that
# `rosnode kill` ends the node promptly even though it is waiting for a key.
SHUTDOWN_POLL_S = 0.1


@dataclass(frozen=True)
class TeleopConfig:
    """Velocity per key press: scale_linear in m/s, scale_angular in rad/s."""

    scale_linear: float = DEFAULT_SCALE
    scale_angular: float = DEFAULT_SCALE

    def __post_init__(self):
        for name in ("scale_linear", "scale_angular"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f"{name} must be a number, got {value!r}")
            if not math.isfinite(value):
                raise ValueError(f"{name} must be finite, got {value!r}")
            object.__setattr__(self, name, float(value))


def key_to_command(key, config):
    """Map one input byte to (linear_x, angular_z), or None when the byte publishes nothing.

    key is an int 0..255 (one byte read from the terminal). Up/down give +/-scale_linear,
    left gives +scale_angular (counter-clockwise), right gives -scale_angular. 'q' is not a
    motion key either: the caller checks is_quit_key() first.
    """
    if isinstance(key, bool) or not isinstance(key, int) or not 0 <= key <= 255:
        raise ValueError(f"key must be a byte value 0..255, got {key!r}")
    if key == KEY_UP:
        return (config.scale_linear, 0.0)
    if key == KEY_DOWN:
        return (-config.scale_linear, 0.0)
    if key == KEY_LEFT:
        return (0.0, config.scale_angular)
    if key == KEY_RIGHT:
        return (0.0, -config.scale_angular)
    return None


def is_quit_key(key):
    """True for the byte that ends the teleop ('q')."""
    return key == KEY_QUIT


class RawTerminal:
    """Context manager: the terminal on fd in non-canonical, no-echo mode, one byte per read.

    The previous settings come back on exit, whatever ends the block (q, SIGINT, shutdown).
    """

    def __init__(self, fd):
        self._fd = fd
        self._saved = None

    def __enter__(self):
        self._saved = termios.tcgetattr(self._fd)
        raw = termios.tcgetattr(self._fd)
        raw[3] &= ~(termios.ICANON | termios.ECHO)  # lflags
        raw[6][termios.VMIN] = 1
        raw[6][termios.VTIME] = 0
        termios.tcsetattr(self._fd, termios.TCSANOW, raw)
        return self

    def __exit__(self, *exc):
        termios.tcsetattr(self._fd, termios.TCSANOW, self._saved)
        return False


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
                if not self.handle_key(data[0]):
                    return 0
        return 0


def load_config():
    """Read scale_linear/scale_angular from the node namespace into a TeleopConfig."""
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
    rospy.init_node("teleop_turtle")
    try:
        config = load_config()
    except ValueError as err:
        rospy.logfatal("turtle_teleop_key: bad parameter: %s", err)
        sys.exit(1)
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
