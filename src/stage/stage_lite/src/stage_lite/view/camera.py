"""What the Stage window looks at (pure: no rospy, no Tk): Stage 4.3's orthographic camera.

Stage's window shows the world through a camera (libstage/camera.cc, OrthoCamera): a centre
point, a scale in pixels per metre and a yaw in degrees (the world file's
``window( center [x y] scale s rotate [pitch yaw] )``). The window centre shows the camera
centre; the view is turned by -yaw, so ``rotate [0 -1.56]`` turns the world 1.56 degrees
clockwise... no: counter-clockwise on screen, as glRotatef(-yaw) does. Pitch tilts Stage's
3D view; the window here is 2D and ignores it.

Camera.to_px/to_world map world points to pixels (rows grow downwards) and back; panned,
zoomed and resized are the mouse and the window frame (drag, wheel about the pointer, a new
window size keeps the centre and scale). window_camera reads the world's window block.
"""
import math
from dataclasses import dataclass, replace

import numpy as np
from course_common.finite import is_finite_number

#: stageros opens its window at 600 x 400 (stage_ros: new Stg::WorldGui(600, 400, ...)).
DEFAULT_SIZE_PX = (600, 400)
#: Stage's window cannot be made smaller than this (size_range(100, 100)).
MIN_SIZE_PX = 100
#: One wheel notch zooms by this factor (OrthoCamera::scale's factor for one notch).
ZOOM_STEP = 1.1
#: More notches at once than this are as many as this (1.1 ** 300 is past any bound below).
MAX_NOTCHES = 300
#: The scale stays within these bounds, px per m, however far the wheel turns.
MIN_SCALE, MAX_SCALE = 0.05, 5000.0
#: Without a window scale, the robots' starts and this much around them fill the window, m.
ROBOTS_MARGIN_M = 4.0


@dataclass(frozen=True)
class Camera:
    """A view of the world: centre (m), scale (px per m), yaw (degrees), size (px)."""

    center_x: float
    center_y: float
    scale: float
    yaw_deg: float
    width_px: int
    height_px: int

    @property
    def size_px(self):
        return self.width_px, self.height_px

    def _rotation(self):
        a = math.radians(self.yaw_deg)
        return math.cos(a), math.sin(a)

    def to_px(self, xy):
        """N x 2 world points to N x 2 pixel coordinates (x right, y down; the window's
        centre is the camera centre)."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        c, s = self._rotation()
        dx, dy = xy[:, 0] - self.center_x, xy[:, 1] - self.center_y
        # turned by -yaw, as Stage's glRotatef(-yaw) turns the model view
        u, v = c * dx + s * dy, -s * dx + c * dy
        return np.column_stack((self.width_px / 2.0 + u * self.scale,
                                self.height_px / 2.0 - v * self.scale))

    def to_world(self, px):
        """N x 2 pixel coordinates to N x 2 world points (the inverse of to_px)."""
        px = np.asarray(px, dtype=float).reshape(-1, 2)
        c, s = self._rotation()
        u = (px[:, 0] - self.width_px / 2.0) / self.scale
        v = (self.height_px / 2.0 - px[:, 1]) / self.scale
        return np.column_stack((self.center_x + c * u - s * v, self.center_y + s * u + c * v))

    def affine_to_world(self):
        """(a, b, c, d, e, f): world x = a*col + b*row + c, world y = d*col + e*row + f."""
        (c0x, c0y), (c1x, c1y), (c2x, c2y) = self.to_world([(0, 0), (1, 0), (0, 1)]).tolist()
        return (c1x - c0x, c2x - c0x, c0x, c1y - c0y, c2y - c0y, c0y)

    def panned(self, dx_px, dy_px):
        """The view after the mouse dragged the world by (dx, dy) px: what was under the
        pointer stays under it (OrthoCamera::move(-dx, dy))."""
        (x0, y0), (x1, y1) = self.to_world([(0.0, 0.0), (dx_px, dy_px)]).tolist()
        return replace(self, center_x=self.center_x - (x1 - x0),
                       center_y=self.center_y - (y1 - y0))

    def zoomed(self, notches, at_px):
        """The view after the wheel turned notches (> 0: in) with the pointer at at_px; the
        world point under the pointer stays under it."""
        factor = ZOOM_STEP ** max(-MAX_NOTCHES, min(MAX_NOTCHES, notches))
        scale = min(MAX_SCALE, max(MIN_SCALE, self.scale * factor))
        (wx, wy), = self.to_world([at_px]).tolist()
        zoomed = replace(self, scale=scale)
        (nx, ny), = zoomed.to_world([at_px]).tolist()
        return replace(zoomed, center_x=self.center_x + wx - nx,
                       center_y=self.center_y + wy - ny)

    def resized(self, width_px, height_px):
        """The same centre and scale in a window of another size."""
        return replace(self, width_px=max(1, int(width_px)), height_px=max(1, int(height_px)))


def _pair(value):
    """Two finite numbers from a window property, else None."""
    try:
        a, b = (float(v) for v in value)
    except (TypeError, ValueError):
        return None
    return (a, b) if is_finite_number(a) and is_finite_number(b) else None


def window_size(window, screen_px=None):
    """The window's size: `size [w h]` (a negative value: the screen's, as in Stage), else
    stageros's 600 x 400; never below Stage's 100 x 100 nor above the screen."""
    size = _pair((window or {}).get('size'))
    w, h = DEFAULT_SIZE_PX if size is None else (int(size[0]), int(size[1]))
    if screen_px is not None:
        w = screen_px[0] if w < 0 else min(w, screen_px[0])
        h = screen_px[1] if h < 0 else min(h, screen_px[1])
    return max(MIN_SIZE_PX, w), max(MIN_SIZE_PX, h)


def robots_box(starts, floor_bounds):
    """(x0, y0, x1, y1): the robots' start positions with ROBOTS_MARGIN_M around them, or the
    floor's bounds when the world has no robot."""
    if not len(starts):
        return floor_bounds
    xs = [p[0] for p in starts]
    ys = [p[1] for p in starts]
    m = ROBOTS_MARGIN_M
    return min(xs) - m, min(ys) - m, max(xs) + m, max(ys) + m


def window_camera(window, size_px, box):
    """The camera the world's window block asks for, filling what it leaves out so that the
    robots are in view: no `center`, the centre of box (robots_box); no `scale`, the largest
    scale that shows all of box. `rotate [pitch yaw]`: yaw in degrees; pitch is ignored."""
    window = window or {}
    w, h = size_px
    x0, y0, x1, y1 = box
    center = _pair(window.get('center')) or ((x0 + x1) / 2.0, (y0 + y1) / 2.0)
    try:
        scale = float(window['scale'])
    except (KeyError, TypeError, ValueError):
        scale = math.nan
    if not (is_finite_number(scale) and scale > 0):
        scale = min(w / max(x1 - x0, 1e-6), h / max(y1 - y0, 1e-6))
    rotate = _pair(window.get('rotate')) or (0.0, 0.0)
    return Camera(center[0], center[1], min(MAX_SCALE, max(MIN_SCALE, scale)), rotate[1], w, h)
