"""Pictures of a Stage world as Stage's window draws it (Pillow + numpy, no rospy, no Tk).

One renderer for the window and ~save_image: floor_image draws what stands still (Stage's
checkered grid over the world's extent, the floor plan, the axis labels) for a camera.Camera,
once per view; render lays what moves over a copy of it: the rangers' fans, the trails, the
robots' bodies with their noses, and the status line. Everything comes in as plain data (an
occupancy grid, RobotView tuples), so this module is tested without a simulator.
"""
import math
from dataclasses import dataclass

import numpy as np
from course_common.finite import is_finite_number
from course_common.trail import Trails

from ..model.floor import coarsen

#: Stage's canvas around the world (glClearColor(0.7, 0.7, 0.8)).
OUTSIDE_RGB = (179, 179, 204)
FREE_RGB = (255, 255, 255)
#: The other square of Stage's checkered floor: one metre squares, 255 and 245 in red and
#: green (Canvas::InitGl's checkImage).
CHECK_RGB = (245, 245, 255)
WALL_RGB = (77, 77, 77)        # Stage's gray30 floor plan
OUTLINE_RGB = (0, 0, 0)
LABEL_RGB = (51, 51, 51)       # the grid's axis labels (Stage: 0.2 grey)
CLOCK_BOX_RGB = (204, 204, 255)  # the status line's pale blue box
#: Ranger fans: the robot's colour laid over what is below at this opacity, as Stage draws
#: them light and see-through: walls stay readable and overlapping fans show each other.
FAN_ALPHA = 0.15
#: The status line's box: at least this wide, and this margin around the text, px (Stage).
CLOCK_MIN_WIDTH_PX, CLOCK_MARGIN_PX = 200, 5


@dataclass(frozen=True)
class DrawOptions:
    """What the window shows (Stage's View menu and the window block's show_* flags)."""

    data: bool = True      # show_data: ranger fans (Stage's default is off: 'd' shows them)
    grid: bool = True      # show_grid: the checkered floor and axis labels
    clock: bool = True     # show_clock: the status line
    trails: bool = False   # show_trailfast: each robot's recent path


#: The window block's flags and the options they set.
SHOW_FLAGS = {'show_data': 'data', 'show_grid': 'grid', 'show_clock': 'clock',
              'show_trailfast': 'trails'}


def draw_options(window):
    """DrawOptions of a world's window block (dict of its properties; None: no block)."""
    values = {}
    for flag, field in SHOW_FLAGS.items():
        value = (window or {}).get(flag)
        if is_finite_number(value):
            values[field] = int(value) != 0   # Stage reads the flags with ReadInt
    return DrawOptions(**values)


@dataclass(frozen=True)
class ScanView:
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
    scans: tuple = ()
    trail: np.ndarray | None = None  # K x 2 world points, oldest first
    #: The body's polygons in the robot frame (the model's blocks); () = the size rectangle.
    body: tuple = ()
    nose: bool = True              # gui_nose: a line from the pose to the front edge


def world_bounds(occupancy):
    """(x0, y0, x1, y1): the occupancy grid's extent."""
    grid, ox, oy, res = occupancy
    rows, cols = grid.shape
    return ox, oy, ox + cols * res, oy + rows * res


class FloorPlan:
    """The static picture of a world: its occupancy grid and extent, drawn for any camera.

    Zoomed out, a pixel covers several cells: the grid is shrunk first (a cell is a wall if
    any cell under it is, floor.coarsen), so thin walls never vanish; each shrink factor
    is computed once.
    """

    def __init__(self, occupancy, extent):
        self.occupancy = occupancy
        self.extent = extent          # (x0, y0, x1, y1): the world's floor, m
        self._shrunk = {}

    def _grid(self, scale):
        grid, _, _, res = self.occupancy
        factor = max(1, int(1.0 / (scale * res)))
        if factor not in self._shrunk:
            self._shrunk[factor] = coarsen(np.asarray(grid, dtype=bool), factor)
        return self._shrunk[factor], res * factor

    def image(self, camera, grid_on=True):
        """An RGB picture of camera's view: Stage's clear colour around the world's extent,
        the checkered floor (or white) inside it, the walls, and the axis labels."""
        from PIL import Image  # only when a picture is drawn: stageros starts without PIL
        w, h = camera.size_px
        a, b, c, d, e, f = camera.affine_to_world()
        cols = np.arange(w, dtype=np.float64) + 0.5      # pixel centres
        rows = np.arange(h, dtype=np.float64)[:, None] + 0.5
        wx = a * cols + b * rows + c
        wy = d * cols + e * rows + f
        x0, y0, x1, y1 = self.extent
        rgb = np.empty((h, w, 3), np.uint8)
        rgb[...] = OUTSIDE_RGB
        inside = (wx >= x0) & (wx < x1) & (wy >= y0) & (wy < y1)
        rgb[inside] = FREE_RGB
        if grid_on:
            odd = ((np.floor(wx) + np.floor(wy)) % 2 == 1) & inside
            rgb[odd] = CHECK_RGB
        cells, res = self._grid(camera.scale)
        _, ox, oy, _ = self.occupancy
        ci = np.floor((wx - ox) / res).astype(np.int64)
        ri = np.floor((wy - oy) / res).astype(np.int64)
        on_grid = (ci >= 0) & (ci < cells.shape[1]) & (ri >= 0) & (ri < cells.shape[0])
        wall = np.zeros((h, w), bool)
        wall[on_grid] = cells[ri[on_grid], ci[on_grid]]
        rgb[wall] = WALL_RGB
        image = Image.fromarray(rgb, 'RGB')
        if grid_on:
            _axis_labels(image, camera, self.extent)
        return image


def _axis_labels(image, camera, extent):
    """Canvas::DrawGlobalGrid's labels: whole metres along both axes, every `skip` metres."""
    from PIL import ImageDraw
    skip = max(1, int(50 / camera.scale))
    if skip > 2 and skip % 2:
        skip += 1
    x0, y0, x1, y1 = extent
    points = [(i, 0.0) for i in range(0, int(math.ceil(x1)), skip)]
    points += [(-i, 0.0) for i in range(skip, int(math.floor(-x0)) + 1, skip)]
    points += [(0.0, i) for i in range(skip, int(math.ceil(y1)), skip)]
    points += [(0.0, -i) for i in range(skip, int(math.floor(-y0)) + 1, skip)]
    draw = ImageDraw.Draw(image)
    w, h = image.size
    for (x, y), (px, py) in zip(points, camera.to_px(points).tolist(), strict=True):
        if 0 <= px < w and 0 <= py < h:
            draw.text((px, py - 10), '%d' % (x if y == 0.0 else y), fill=LABEL_RGB)


def _rgb255(color):
    return tuple(round(255 * max(0.0, min(1.0, c))) for c in color)


def transformed(pose, local):
    """N x 2 points given in the frame pose (x, y, yaw) as N x 2 points in the outer frame."""
    x, y, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    local = np.asarray(local, dtype=float).reshape(-1, 2)
    return np.column_stack((x + c * local[:, 0] - s * local[:, 1],
                            y + s * local[:, 0] + c * local[:, 1]))


def footprint(robot):
    """The robot's body as world polygons (N x 2 each): its blocks, else its size rectangle."""
    if robot.body:
        return [transformed(robot.pose, poly) for poly in robot.body]
    (sx, sy), (ox, oy) = robot.size, robot.origin
    corners = [(ox - sx / 2, oy - sy / 2), (ox + sx / 2, oy - sy / 2),
               (ox + sx / 2, oy + sy / 2), (ox - sx / 2, oy + sy / 2)]
    return [transformed(robot.pose, corners)]


def fan_polygon(robot, scan):
    """The area a ranger sees: its origin and every beam's end, (samples + 1) x 2 world points."""
    sx, sy, syaw = scan.pose
    (ox, oy), = transformed(robot.pose, [(sx, sy)])
    heading = robot.pose[2] + syaw + np.asarray(scan.angles, dtype=float)
    r = np.asarray(scan.ranges, dtype=float)
    ends = np.column_stack((ox + r * np.cos(heading), oy + r * np.sin(heading)))
    return np.vstack(([ox, oy], ends))


def _points(camera, xy, simplify=False):
    """camera's pixels of the world points xy, whole pixels, a flat [x0, y0, x1, ...] list
    as ImageDraw takes it, without a point repeating the one before (a fan of 1081 beams
    has about 800 distinct corners in the lesson's window). simplify: also without the
    corners that lie on a straight run (_simplified): Pillow fills a polygon scanning every
    edge on every row, so a fan along a wall fills in half the time, the same to a pixel."""
    px = np.rint(camera.to_px(xy)).astype(np.int64)
    keep = np.ones(len(px), bool)
    keep[1:] = (px[1:] != px[:-1]).any(axis=1)
    px = px[keep]
    return (_simplified(px) if simplify else px).ravel().tolist()


#: _simplified drops a corner closer than this to the line through its neighbours, px, in
#: each of SIMPLIFY_PASSES passes (so the outline moves by less than a pixel in all).
SIMPLIFY_TOL_PX, SIMPLIFY_PASSES = 0.3, 3


def _simplified(px):
    """The polygon px (N x 2) without the corners on straight runs: each pass tests every
    other corner against its two neighbours, so a pass never drops two corners in a row."""
    for _ in range(SIMPLIFY_PASSES):
        if len(px) < 5:
            break
        mid = px[1:-1:2]
        before, after = px[0:-2:2], px[2::2]
        chord = (after - before).astype(float)
        cross = np.abs(chord[:, 0] * (mid[:, 1] - before[:, 1])
                       - chord[:, 1] * (mid[:, 0] - before[:, 0]))
        straight = cross <= SIMPLIFY_TOL_PX * np.hypot(chord[:, 0], chord[:, 1])
        keep = np.ones(len(px), bool)
        keep[1:-1:2] = ~straight
        px = px[keep]
    return px


def _draw_fans(camera, image, robots):
    """Every ranger's fan laid over image at FAN_ALPHA in its robot's colour (fans drawn
    later mix with earlier ones instead of hiding them): Pillow blends an RGBA fill into the
    RGB picture as it fills the polygon, about 1 ms a frame for the lesson."""
    from PIL import ImageDraw
    draw = ImageDraw.Draw(image, 'RGBA')
    opacity = round(FAN_ALPHA * 255)
    for robot in robots:
        fill = (*_rgb255(robot.color), opacity)
        for scan in robot.scans:
            corners = (_points(camera, fan_polygon(robot, scan), simplify=True)
                       if len(scan.ranges) else [])
            if len(corners) >= 6:
                draw.polygon(corners, fill=fill)


def _draw_status(image, text):
    """Stage's clock box: black text on pale blue, at the bottom left."""
    from PIL import ImageDraw
    draw = ImageDraw.Draw(image)
    left, top, right, bottom = draw.textbbox((0, 0), text)
    width = max(CLOCK_MIN_WIDTH_PX, right - left) + 2 * CLOCK_MARGIN_PX
    height = (bottom - top) + 2 * CLOCK_MARGIN_PX
    h = image.size[1]
    draw.rectangle((0, h - height, width, h), fill=CLOCK_BOX_RGB)
    draw.text((CLOCK_MARGIN_PX - left, h - height + CLOCK_MARGIN_PX - top), text,
              fill=OUTLINE_RGB)


def render(camera, base, robots, options=DrawOptions(), status=None):
    """A copy of base (FloorPlan.image of camera) with the fans (options.data), the trails
    (options.trails), the robots and, with options.clock, the status line drawn on it."""
    from PIL import ImageDraw  # only when a picture is drawn: stageros starts without PIL
    image = base.copy()
    if options.data:
        _draw_fans(camera, image, robots)
    draw = ImageDraw.Draw(image)
    if options.trails:
        for robot in robots:
            if robot.trail is not None and len(robot.trail) > 1:
                draw.line(_points(camera, robot.trail), fill=_rgb255(robot.color), width=1)
    for robot in robots:
        for polygon in footprint(robot):
            corners = _points(camera, polygon)
            if len(corners) >= 6:
                draw.polygon(corners, fill=_rgb255(robot.color), outline=OUTLINE_RGB)
            else:   # zoomed far out: a dot, never nothing
                draw.point(corners[:2], fill=_rgb255(robot.color))
        if robot.nose:
            front = robot.origin[0] + robot.size[0] / 2
            draw.line(_points(camera, transformed(robot.pose, [(0.0, 0.0), (front, 0.0)])),
                      fill=OUTLINE_RGB, width=1)
    if options.clock and status is not None:
        _draw_status(image, status)
    return image


def trails(count, min_step_m=0.05, max_points=2000):
    """The robots' trails a picture draws: a point whenever a robot moved min_step_m, the
    last max_points (course_common.trail.Trails)."""
    return Trails(count, max_points, min_step_m)
