"""Pictures of the simulator: the canvas with a vector turtle sprite per turtle (Pillow, no rospy).

turtlesim draws 45 px bitmap sprites; turtle_lite draws its own simple turtle (shell, head,
four legs, tail) of about the same size, rotated by theta. Sprites go on a copy of the
canvas, never on the canvas itself, so color_sensor never sees them (as in turtlesim).
"""

import math

from course_common.arena import METER_PX, WORLD_SIZE_M
from course_common.save_image import write_png
from PIL import Image, ImageDraw

SHELL_RGB = (46, 139, 87)
SHELL_EDGE_RGB = (20, 70, 40)
SKIN_RGB = (152, 205, 120)
#: Sprite outline in sprite units (1 unit = 1 px), turtle facing +x, y up.
_HEAD = [(14 + 5 * math.cos(a), 5 * math.sin(a)) for a in
         (2 * math.pi * k / 12 for k in range(12))]
_LEGS = [[(cx - 4, cy - 3), (cx + 4, cy - 3), (cx + 4, cy + 3), (cx - 4, cy + 3)]
         for cx in (-8, 8) for cy in (-11, 11)]
_TAIL = [(-13, -2), (-19, 0), (-13, 2)]
_SHELL = [(12 * math.cos(a), 10 * math.sin(a)) for a in
          (2 * math.pi * k / 20 for k in range(20))]
_SHELL_MARK = [(5 * math.cos(a), 4 * math.sin(a)) for a in
               (2 * math.pi * k / 6 for k in range(6))]


def _place(points, cx, cy, theta):
    """Rotate sprite points by theta (counter-clockwise in the world) and move to (cx, cy)
    in pixel coordinates, where rows grow downwards."""
    c = math.cos(theta)
    s = math.sin(theta)
    return [(cx + c * px - s * py, cy - (s * px + c * py)) for px, py in points]


def draw_turtle(draw, x, y, theta):
    """Draw one turtle sprite at world pose (x, y, theta) on a Pillow ImageDraw."""
    cx = x * METER_PX
    cy = (WORLD_SIZE_M - y) * METER_PX
    for leg in _LEGS:
        draw.polygon(_place(leg, cx, cy, theta), fill=SKIN_RGB, outline=SHELL_EDGE_RGB)
    draw.polygon(_place(_TAIL, cx, cy, theta), fill=SKIN_RGB, outline=SHELL_EDGE_RGB)
    draw.polygon(_place(_HEAD, cx, cy, theta), fill=SKIN_RGB, outline=SHELL_EDGE_RGB)
    draw.polygon(_place(_SHELL, cx, cy, theta), fill=SHELL_RGB, outline=SHELL_EDGE_RGB)
    draw.polygon(_place(_SHELL_MARK, cx, cy, theta), outline=SHELL_EDGE_RGB)


def render(pixels, poses):
    """A Pillow RGB image: the canvas ``pixels`` (H x W x 3 uint8) with a sprite per pose.

    ``poses`` is an iterable of (x, y, theta) in world units.
    """
    image = Image.fromarray(pixels, 'RGB')
    draw = ImageDraw.Draw(image)
    for x, y, theta in poses:
        draw_turtle(draw, x, y, theta)
    return image


def save_png(path, pixels, poses):
    """Write the rendered picture to ``path`` (directories created); returns the absolute path."""
    return write_png(path, render(pixels, poses))
