"""Stage 4.3's camera model (libstage/model_camera.cc) and what stageros publishes of it.

Camera: the model as ModelCamera's constructor and Load() make it: a black 0.1 x 0.07 x
0.05 m body; `resolution [w h]` (pixels, default 32 x 32), `range [near far]` (m, default
[0.2 8.0]), `fov [horizontal vertical]` (degrees, default [70 40]), `pantilt [pan tilt]`
(degrees, default [0 0]; a positive pan turns the view right, a positive tilt down).

Where Stage looks from (ModelCamera::GetFrame): the eye is at the PARENT's x, y and at the
camera's own global z (its base: the parent's height plus the camera's pose z); it looks
along the parent's heading turned by -pan and tilted down by tilt. The camera's own x, y
offset and yaw are not used for the view (stageros's tf does use them). A frame is the
depth and colour of Stage's GL drawing of the floor and every model's blocks (camera_render).

CameraView: what stageros publishes of a camera on a position model (image, depth,
camera_info, tf base_link -> camera), with the frame of its last update. The camera is
updated, like every Stage model, in the world's synchronous queue: before this step's moves
(the poses the step starts from). ModelCamera's constructor starts its update chain with the
default 100 ms interval and stageros's Subscribe() starts another with update_interval: a
frame is made at every time of either chain.
"""
import math

import numpy as np

from .models import Model

CAMERA_SIZE = (0.1, 0.07, 0.05)       # model_camera.cc DEFAULT_SIZE
DEFAULT_RESOLUTION = (32, 32)         # ModelCamera's _width, _height
DEFAULT_RANGE = (0.2, 8.0)            # CAMERA_NEAR_CLIP, CAMERA_FAR_CLIP, m
DEFAULT_FOV_DEG = (70.0, 40.0)        # DEFAULT_HFOV, DEFAULT_VFOV
CONSTRUCTOR_INTERVAL_US = 100000      # Model's default interval when the constructor starts
#: stageros's window (WorldGui(600, 400)) and FLTK's menu bar above Stage's canvas (30 px):
#: GetFrame cuts a resolution larger than the canvas down to the canvas.
STAGEROS_WINDOW = (600, 400)
MENU_BAR_PX = 30


class Camera(Model):
    """ModelCamera: its body and its properties (see the module docstring)."""

    def construct(self):
        self.set_geom((0.0, 0.0, 0.0, 0.0), CAMERA_SIZE)
        self.color = (0.0, 0.0, 0.0, 1.0)
        self.resolution = DEFAULT_RESOLUTION
        self.range = DEFAULT_RANGE
        self.fov_deg = DEFAULT_FOV_DEG
        self.pantilt_deg = (0.0, 0.0)
        self.problems = []      # (path, line, what): why this camera makes no frame
        self.where = ('?', 0)   # its entity's file and line

    def load(self, wf, rand48):
        """Model::Load, then ModelCamera::Load's four tuples ('ff', 'll', 'ff', 'ii')."""
        super().load(wf, rand48)
        e = self.entity
        self.where = (wf.entities[e].path, wf.entities[e].line)
        self.fov_deg = tuple(wf.read_tuple(e, 'fov', 'ff') or self.fov_deg)
        self.range = tuple(wf.read_tuple(e, 'range', 'll') or self.range)
        self.pantilt_deg = tuple(wf.read_tuple(e, 'pantilt', 'ff') or self.pantilt_deg)
        self.resolution = tuple(wf.read_tuple(e, 'resolution', 'ii') or self.resolution)
        self.problems = self._check(wf)

    def _check(self, wf):
        """The values Stage cannot make a frame of: [(path, line, what)]."""
        ent = wf.entities[self.entity]

        def where(name):
            p = wf.prop(self.entity, name)
            return (p.path, p.line) if p else (ent.path, ent.line)

        out = []
        w, h = self.resolution
        if w <= 0 or h <= 0:
            stage = ('makes no frame' if w == 0 or h == 0
                     else 'crashes allocating its frame')
            out.append(where('resolution') + (
                'camera %s: resolution [%d %d] has no pixels (Stage %s): its image, depth'
                ' and camera_info are not published' % (self.token, w, h, stage),))
        hf, vf = self.fov_deg
        if not (0.0 < hf < 180.0 and 0.0 < vf < 180.0):
            out.append(where('fov') + (
                'camera %s: fov [%g %g] must lie strictly between 0 and 180 degrees (Stage\'s'
                ' projection is degenerate): not published' % (self.token, hf, vf),))
        near, far = self.range
        if not (0.0 < near < far) or not math.isfinite(far):
            out.append(where('range') + (
                'camera %s: range [%g %g] must be 0 < near < far (OpenGL refuses the'
                ' projection): not published' % (self.token, near, far),))
        return out

    def eye(self):
        """(x, y, z, heading rad, pan deg, tilt deg): where GetFrame puts its GL camera."""
        px, py, _, pa = self.parent.global_pose()
        return (px, py, self.global_pose()[2], pa, self.pantilt_deg[0], self.pantilt_deg[1])

    def stage_yaw_pitch_deg(self):
        """PerspectiveCamera's yaw and pitch as GetFrame sets them, in degrees."""
        pa = self.parent.global_pose()[3]
        return (math.degrees(pa) - 90.0 - self.pantilt_deg[0], 90.0 - self.pantilt_deg[1])


def canvas_size(window):
    """Stage's canvas (width, height) in stageros's window: the world's `window( size )` or
    stageros's 600 x 400, less the menu bar."""
    size = (window or {}).get('size')
    w, h = STAGEROS_WINDOW
    if isinstance(size, list) and len(size) >= 2:
        w, h = int(size[0]), int(size[1])
    return w, h - MENU_BAR_PX


class CameraView:
    """What stageros publishes of one camera: sizes, intrinsics, the tf pose and the last
    frame (depth float32 (h, w) in m: planar depth along the view axis, inf where nothing
    was drawn within `far`; rgba uint8 (h, w, 4)), row 0 the top of the picture (stageros
    flips OpenGL's rows)."""

    def __init__(self, model, robot_height, canvas):
        self.model = model
        w, h = model.resolution
        # GetFrame: a resolution larger than the canvas is cut to it
        self.width = min(w, canvas[0])
        self.height = min(h, canvas[1])
        self.clipped = (self.width, self.height) != (w, h)
        self.near, self.far = model.range
        self.hfov_deg, self.vfov_deg = model.fov_deg
        x, y, z, a = model.pose
        self.tf_xyz = (x, y, robot_height + z)     # base_link -> camera, as stageros sends it
        self.local_yaw = a
        self.depth = None
        self.rgba = None
        self.has_data = False
        self.next_us = [CONSTRUCTOR_INTERVAL_US, model.interval_us]

    def due(self, now_us):
        """True when either update chain (module docstring) reaches now_us; advances them."""
        hit = False
        for k, t in enumerate(self.next_us):
            if t <= now_us:
                hit = True
                self.next_us[k] = now_us + self.model.interval_us
        return hit

    def intrinsics(self):
        """stageros's (fx, fy, cx, cy): w / (2 tan(hfov / 2)), h / (2 tan(vfov / 2)), w / 2,
        h / 2."""
        fovh = self.hfov_deg * math.pi / 180.0
        fovv = self.vfov_deg * math.pi / 180.0
        return (self.width / (2 * math.tan(fovh / 2)), self.height / (2 * math.tan(fovv / 2)),
                self.width / 2.0, self.height / 2.0)

    def tf_rpy(self, robot_yaw_local):
        """stageros's base_link -> camera rotation: roll = pitch - pi, pitch 0, yaw = the
        camera's yaw + the GL camera's yaw - the robot's own yaw (radians, its order of
        operations)."""
        yaw_deg, pitch_deg = self.model.stage_yaw_pitch_deg()
        return ((pitch_deg * math.pi / 180.0) - math.pi, 0.0,
                self.local_yaw + (yaw_deg * math.pi / 180.0) - robot_yaw_local)

    def store(self, depth, rgba):
        self.depth = np.asarray(depth, np.float32)
        self.rgba = np.asarray(rgba, np.uint8)
        self.has_data = True


class CameraRig:
    """Every camera stageros publishes (the cameras whose parent is a position model), per
    robot, and the scene they draw; update() makes the frames due at a step."""

    def __init__(self, models, robots, statics, ppm, window, warnings):
        from .camera_render import Scene  # numba's kernels only when a world has cameras
        self.by_robot = [[] for _ in robots]
        robot_of = {r.model.index: i for i, r in enumerate(robots)}
        canvas = canvas_size(window)
        for m in models:
            if not isinstance(m, Camera):
                continue
            where = '%s:%d' % m.where
            i = robot_of.get(m.parent.index) if m.parent is not None else None
            if i is None:
                warnings.append('%s: camera %s is not on a position model: stageros publishes'
                                ' nothing of it (a body only)' % (where, m.token))
                continue
            if m.problems:
                warnings.extend('%s:%s: %s' % p for p in m.problems)
                continue
            view = CameraView(m, robots[i].model.geom_size[2], canvas)
            if view.clipped:
                warnings.append('%s: camera %s: resolution [%d %d] is larger than Stage\'s'
                                ' canvas (%d x %d): Stage cuts it to [%d %d]'
                                % (where, m.token, m.resolution[0], m.resolution[1],
                                   canvas[0], canvas[1], view.width, view.height))
            self.by_robot[i].append(view)
        self.views = [v for vs in self.by_robot for v in vs]
        self.scene = None
        if self.views:
            static_ids = {m.index for m in statics}
            self.scene = Scene(models, {m.index for m in models if m.index not in static_ids},
                               ppm)

    def update(self, now_us):
        """ModelCamera::Update of every camera due at now_us (before the step's moves)."""
        due = [v for v in self.views if v.due(now_us)]
        if not due:
            return
        self.scene.refresh()
        for v in due:
            self.render(v)

    def render(self, view):
        x, y, z, _, _, _ = view.model.eye()
        yaw_deg, pitch_deg = view.model.stage_yaw_pitch_deg()
        depth, _, rgba = self.scene.render((x, y, z), yaw_deg, pitch_deg, view.width,
                                           view.height, view.hfov_deg, view.vfov_deg,
                                           view.near, view.far)
        view.store(depth, rgba)
