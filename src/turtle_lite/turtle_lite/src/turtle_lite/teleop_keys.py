"""turtle_teleop_key's key mapping: one input byte -> (linear_x, angular_z), no ROS.

Mirrors turtlesim's teleop (tutorials/teleop_turtle_key.cpp); the node in
turtle_teleop_key_node.py reads the bytes and publishes the Twists.
"""

from dataclasses import dataclass

from course_common.params import check_number

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


@dataclass(frozen=True)
class TeleopConfig:
    """Velocity per key press: scale_linear in m/s, scale_angular in rad/s."""

    scale_linear: float = DEFAULT_SCALE
    scale_angular: float = DEFAULT_SCALE

    def __post_init__(self):
        # Any finite number, as turtlesim: a negative scale simply reverses the keys.
        for name in ("scale_linear", "scale_angular"):
            object.__setattr__(self, name, check_number(name, getattr(self, name)))


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
