"""Pictures of a Stage world: floor plan, laser beams, trails and robots (Pillow + numpy, no rospy).

The ~save_image service and the Tk window draw with render(). Everything comes in as plain
data (an occupancy grid, RobotView tuples), so this module is tested without a simulator.
Beams are drawn as one filled polygon per ranger (the region the laser sees), not 1081 lines.
"""
import math
from dataclasses import dataclass

import numpy as np
from course_common.trail import Trail

FREE_RGB = (255, 255, 255)
WALL_RGB = (77, 77, 77)        # Stage's gray30 floor plan
OUTLINE_RGB = (0, 0, 0)
#: Ranger fans: the robot's colour laid over what is below at this opacity, as Stage draws
#: them light and see-through: walls stay readable and overlapping fans show each other.
FAN_ALPHA = 0.15
#: Margin around the floor plan and robots, m.
MARGIN_M = 0.5
#: A cell counts as wall in a shrunk picture when its mean grey falls below this (any wall
#: cell under the pixel darkens it; thin walls must not vanish when the picture is smaller).
WALL_THRESHOLD = 250


@dataclass(frozen=True)
class RangerView:
    """One ranger as drawn: its pose in the robot frame, beam angles and current ranges."""

    pose: tuple                    # (x, y, yaw) in the robot frame
    angles: np.ndarray             # beam angles in the sensor frame, rad
    ranges: np.ndarray             # m


@dataclass(frozen=True)
class RobotView:
    """One robot as drawn."""

    pose: tuple                    # (x, y, yaw) world
    size: tuple                    # (x, y) m
    origin: tuple                  # (x, y) body offset from the pose, robot frame
    color: tuple                   # (r, g, b) 0..1
    rangers: tuple = ()
    trail: np.ndarray | None = None  # K x 2 world points, oldest first


@dataclass(frozen=True)
class View:
    """World rectangle [x0, x1] x [y0, y1] drawn at scale px per m."""

    x0: float
    y0: float
    x1: float
    y1: float
    scale: float

    @property
    def size_px(self):
        return (max(1, math.ceil((self.x1 - self.x0) * self.scale)),
                max(1, math.ceil((self.y1 - self.y0) * self.scale)))

    def to_px(self, xy):
        """N x 2 world points to N x 2 pixel coordinates (rows grow downwards)."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        return np.column_stack(((xy[:, 0] - self.x0) * self.scale,
                                (self.y1 - xy[:, 1]) * self.scale))


def fit_view(bounds, max_w_px, max_h_px):
    """The View of bounds (x0, y0, x1, y1), margins added, as large as fits max_w x max_h."""
    x0, y0, x1, y1 = bounds
    if not (x1 > x0 and y1 > y0) or max_w_px < 1 or max_h_px < 1:
        raise ValueError('cannot draw bounds %r in %r x %r px' % (bounds, max_w_px, max_h_px))
    x0, y0, x1, y1 = x0 - MARGIN_M, y0 - MARGIN_M, x1 + MARGIN_M, y1 + MARGIN_M
    scale = min(max_w_px / (x1 - x0), max_h_px / (y1 - y0))
    return View(x0, y0, x1, y1, scale)


def world_bounds(occupancy, points=()):
    """(x0, y0, x1, y1) holding the occupancy grid and the given world points."""
    grid, ox, oy, res = occupancy
    rows, cols = grid.shape
    xs = [ox, ox + cols * res] + [p[0] for p in points]
    ys = [oy, oy + rows * res] + [p[1] for p in points]
    return min(xs), min(ys), max(xs), max(ys)


def floor_image(view, occupancy):
    """An RGB image of the view with the occupancy grid's walls (grid row 0 = lowest y)."""
    from PIL import Image  # only when a picture is drawn: stageros starts without PIL
    grid, ox, oy, res = occupancy
    w, h = view.size_px
    rows, cols = grid.shape
    canvas = Image.new('L', (w, h), 255)
    if rows and cols:
        cells = Image.fromarray(np.where(grid[::-1], 0, 255).astype(np.uint8), 'L')
        (left, top), = view.to_px([(ox, oy + rows * res)])
        cw = max(1, round(cols * res * view.scale))
        ch = max(1, round(rows * res * view.scale))
        shrink = Image.BOX if cw < cols else Image.NEAREST
        canvas.paste(cells.resize((cw, ch), shrink), (round(left), round(top)))
    grey = np.asarray(canvas)
    rgb = np.empty((h, w, 3), np.uint8)
    rgb[...] = FREE_RGB
    rgb[grey < WALL_THRESHOLD] = WALL_RGB
    return Image.fromarray(rgb, 'RGB')


def _rgb255(color, tint=1.0):
    return tuple(round(255 * (1.0 - tint * (1.0 - max(0.0, min(1.0, c))))) for c in color)


def _transform(pose, local):
    x, y, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    local = np.asarray(local, dtype=float).reshape(-1, 2)
    return np.column_stack((x + c * local[:, 0] - s * local[:, 1],
                            y + s * local[:, 0] + c * local[:, 1]))


def footprint(robot):
    """The robot's body rectangle as 4 x 2 world points."""
    (sx, sy), (ox, oy) = robot.size, robot.origin
    corners = [(ox - sx / 2, oy - sy / 2), (ox + sx / 2, oy - sy / 2),
               (ox + sx / 2, oy + sy / 2), (ox - sx / 2, oy + sy / 2)]
    return _transform(robot.pose, corners)


def beam_polygon(robot, ranger):
    """The area a ranger sees: its origin and every beam's end, (samples + 1) x 2 world points."""
    sx, sy, syaw = ranger.pose
    (ox, oy), = _transform(robot.pose, [(sx, sy)])
    heading = robot.pose[2] + syaw + np.asarray(ranger.angles, dtype=float)
    r = np.asarray(ranger.ranges, dtype=float)
    ends = np.column_stack((ox + r * np.cos(heading), oy + r * np.sin(heading)))
    return np.vstack(([ox, oy], ends))


def _points(view, xy):
    return [tuple(p) for p in view.to_px(xy).tolist()]


def _with_fans(view, base, robots):
    """A copy of base with every ranger's fan laid over it at FAN_ALPHA in its robot's colour
    (fans drawn later mix with earlier ones instead of hiding them): Pillow blends an RGBA
    fill into the RGB picture as it fills the polygon, about 1 ms a frame for the lesson."""
    from PIL import ImageDraw
    image = base.copy()
    draw = ImageDraw.Draw(image, 'RGBA')
    opacity = round(FAN_ALPHA * 255)
    for robot in robots:
        fill = (*_rgb255(robot.color), opacity)
        for ranger in robot.rangers:
            if len(ranger.ranges):
                draw.polygon(_points(view, beam_polygon(robot, ranger)), fill=fill)
    return image


def render(view, base, robots):
    """A copy of ``base`` (floor_image of view) with beams, trails and robots drawn on it."""
    from PIL import ImageDraw  # only when a picture is drawn: stageros starts without PIL
    image = _with_fans(view, base, robots)
    draw = ImageDraw.Draw(image)
    for robot in robots:
        if robot.trail is not None and len(robot.trail) > 1:
            draw.line(_points(view, robot.trail), fill=_rgb255(robot.color), width=1)
    for robot in robots:
        draw.polygon(_points(view, footprint(robot)), fill=_rgb255(robot.color),
                     outline=OUTLINE_RGB)
        # The nose (Stage's gui_nose): from the pose to the front edge.
        front = robot.origin[0] + robot.size[0] / 2
        draw.line(_points(view, _transform(robot.pose, [(0.0, 0.0), (front, 0.0)])),
                  fill=OUTLINE_RGB, width=1)
    return image


class Trails:
    """The recent path of each robot, for pictures: a point whenever it moved min_step_m
    (course_common.trail.Trail, one per robot)."""

    def __init__(self, count, min_step_m=0.05, max_points=2000):
        self._trails = [Trail(max_points, min_step_m) for _ in range(count)]

    def add(self, index, x, y):
        self._trails[index].add(x, y)

    def clear(self):
        for trail in self._trails:
            trail.clear()

    def get(self, index):
        """K x 2 array of robot index's trail (K may be 0)."""
        return np.asarray(self._trails[index].points(), dtype=float).reshape(-1, 2)
