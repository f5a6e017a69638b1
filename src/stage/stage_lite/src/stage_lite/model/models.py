"""Stage 4.3's models as its constructors and Load() build them from a world file.

Each model has a pose (in its parent's frame), a geometry (`origin` offset and `size`), and a
body of blocks: polygons in the model's frame with a height range. Stage's rules, kept here
in Stage's order because the body's last bits depend on it:
- a new model has one block, the unit square, 1 m tall; every `size` change and a few other
  moments (CalcSize) scale ALL its blocks so their bounding box fills the size (x, y centred,
  z scaled from 0); a `bitmap` replaces the blocks with the image's outline polygons, a
  `block( )` entity with the blocks it defines; `boundary 1` adds four 0.01 m rectangles on
  the edges of the blocks' bounding box; rangers and fiducials start with no block at all;
- a child model stands on its parent: its z starts at the parent's pose z plus the parent's
  size z (`stack_children`, default 1);
- defaults: size [0.4 0.4 1.0] (ranger [0.15 0.15 0.2]), colour red, obstacle_return 1,
  ranger_return 1.0 (negative: invisible to rangers), update_interval 100 ms.
Position and ranger properties are read as Stage's ModelPosition and ModelRanger read them.
"""
import math
import os

import numpy as np

from . import image
from .pose import pose_add, stage_normalize
from .worldfile import WorldError

DEFAULT_SIZE = (0.4, 0.4, 1.0)        # Stage's Size()
RANGER_SIZE = (0.15, 0.15, 0.2)       # ModelRanger: a SICK LMS
CAMERA_SIZE = (0.1, 0.07, 0.05)
BLINKENLIGHT_SIZE = (0.02, 0.02, 0.02)
SENSOR_SIZE = (0.02, 0.02, 0.02)      # a ranger's transducer; its beam leaves at half height
BOUNDARY_WIDTH = 0.01                 # Model::Load's boundary rectangles, m
BILLION = 1e9                         # BlockGroup::BoundingBox's starting extremes
DBL_EPSILON = 2.220446049250313e-16
# ModelPosition's integration error when the world gives no odom_error: each axis drawn once
# in [-E/2, E/2) (the angle's 0.05 is used as radians: it is not read from a file)
INTEGRATION_ERROR_MAX = (0.03, 0.03, 0.0, 0.05)
DEFAULT_INTERVAL_US = 100000
BUILTIN_TYPES = ('model', 'actuator', 'blinkenlight', 'blobfinder', 'bumper', 'camera',
                 'fiducial', 'gripper', 'lightindicator', 'position', 'ranger')
SIMULATED_TYPES = ('model', 'position', 'ranger')
DEFAULT_COLOR = (1.0, 0.0, 0.0, 1.0)  # Stage's Color(): red

# A few X11 names, used when the system's rgb.txt is not there (Stage reads its own copy).
_X11 = {
    'black': (0, 0, 0), 'white': (255, 255, 255), 'red': (255, 0, 0), 'green': (0, 255, 0),
    'blue': (0, 0, 255), 'yellow': (255, 255, 0), 'cyan': (0, 255, 255),
    'magenta': (255, 0, 255), 'gray': (190, 190, 190), 'grey': (190, 190, 190),
    'orange': (255, 165, 0), 'purple': (160, 32, 240), 'brown': (165, 42, 42),
    'pink': (255, 192, 203), 'navy': (0, 0, 128), 'gold': (255, 215, 0),
    'dark green': (0, 100, 0), 'darkgreen': (0, 100, 0), 'dark blue': (0, 0, 139),
    'darkblue': (0, 0, 139), 'dark red': (139, 0, 0), 'darkred': (139, 0, 0),
    'light blue': (173, 216, 230), 'lightblue': (173, 216, 230),
    'light gray': (211, 211, 211), 'lightgray': (211, 211, 211),
    'dark gray': (169, 169, 169), 'darkgray': (169, 169, 169),
}
RGB_TXT = '/usr/share/X11/rgb.txt'
_rgb_table = None


def _colour_table():
    global _rgb_table
    if _rgb_table is None:
        table = dict(_X11)
        try:
            with open(RGB_TXT, encoding='latin-1') as f:
                for line in f:
                    parts = line.split(None, 3)
                    if len(parts) == 4 and not line.startswith(('!', '#', '%')):
                        table[parts[3].strip().lower()] = tuple(int(v) for v in parts[:3])
        except OSError:
            pass
        _rgb_table = table
    return _rgb_table


def colour(name):
    """(r, g, b, a) in 0..1 of an X11 colour name, grayN and #rrggbb included; None for an
    unknown name (Stage then uses red)."""
    key = name.strip().lower()
    rgb = _colour_table().get(key)
    if rgb is None and key.startswith('#') and len(key) == 7:
        try:
            rgb = tuple(int(key[i:i + 2], 16) for i in (1, 3, 5))
        except ValueError:
            rgb = None
    return None if rgb is None else (rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0, 1.0)


class Block:
    """A polygon of the model's body: points (N, 2) in the model's frame, and its height
    range (local z, from the model's base)."""

    def __init__(self, pts, zmin, zmax):
        self.pts = np.array(pts, dtype=np.float64).reshape(-1, 2)
        self.zmin = zmin
        self.zmax = zmax


def rect_block(x, y, dx, dy, dz):
    """Model::AddBlockRect's block."""
    return Block([(x, y), (x + dx, y), (x + dx, y + dy), (x, y + dy)], 0.0, dz)


def bounding_box(blocks):
    """BlockGroup::BoundingBox: (minx, maxx, miny, maxy, minz, maxz), +-1e9 when empty."""
    minx = miny = minz = BILLION
    maxx = maxy = maxz = -BILLION
    for b in blocks:
        if len(b.pts):
            minx = min(minx, float(b.pts[:, 0].min()))
            maxx = max(maxx, float(b.pts[:, 0].max()))
            miny = min(miny, float(b.pts[:, 1].min()))
            maxy = max(maxy, float(b.pts[:, 1].max()))
        minz = min(minz, b.zmin)
        maxz = max(maxz, b.zmax)
    return minx, maxx, miny, maxy, minz, maxz


def _not_zero(v):
    return v if abs(v) >= DBL_EPSILON else DBL_EPSILON


def calc_size(blocks, size):
    """BlockGroup::CalcSize: scale the blocks so their bounding box fills `size` (x, y about
    the box's centre, z from 0), in Stage's order of operations."""
    minx, maxx, miny, maxy, minz, maxz = bounding_box(blocks)
    sx, sy, sz = _not_zero(maxx - minx), _not_zero(maxy - miny), _not_zero(maxz - minz)
    offx = minx + sx / 2.0
    offy = miny + sy / 2.0
    for b in blocks:
        b.pts[:, 0] = (b.pts[:, 0] - offx) * (size[0] / sx)
        b.pts[:, 1] = (b.pts[:, 1] - offy) * (size[1] / sy)
        b.zmin = (b.zmin - 0.0) * (size[2] / sz)
        b.zmax = (b.zmax - 0.0) * (size[2] / sz)


class Sensor:
    """One `sensor( )` of a ranger: pose in the ranger's frame, size, range [min, max] (m),
    fov (rad), samples, noise (constant variance m^2, proportional, angle)."""

    def __init__(self):
        self.pose = (0.0, 0.0, 0.0, 0.0)
        self.size = SENSOR_SIZE
        self.range = (0.0, 5.0)
        self.fov = 0.1
        self.samples = 1
        self.noise = (0.0, 0.0, 0.0)
        self.where = None

    def load(self, wf, e):
        self.where = (wf.entities[e].path, wf.entities[e].line)
        self.pose = read_pose(wf, e, 'pose', self.pose)
        self.size = tuple(wf.read_tuple(e, 'size', 'lll') or self.size)
        self.range = tuple(wf.read_tuple(e, 'range', 'll') or self.range)
        self.fov = wf.read_angle(e, 'fov', self.fov)
        self.samples = wf.read_int(e, 'samples', self.samples)
        self.noise = tuple(wf.read_tuple(e, 'noise', 'lfa') or self.noise)
        read_colour(wf, e, (0.0, 0.0, 1.0, 0.15))
        p = wf.prop(e, 'samples')
        if self.samples < 1:
            raise WorldError(p.path if p else self.where[0], p.line if p else self.where[1],
                             'samples must be at least 1, got %d' % self.samples)


def read_pose(wf, e, name, default):
    """Pose::Load: four values (x, y, z, angle), the angle normalised; default if absent."""
    v = wf.read_tuple(e, name, 'llla')
    if v is None:
        return default
    return (v[0], v[1], v[2], stage_normalize(v[3]))


def read_colour(wf, e, default):
    """Model::Load's and Color::Load's colour: `color` by name, else `color_rgba`."""
    if wf.exists(e, 'color'):
        name = wf.read_string(e, 'color', '')
        if name == '':
            return default
        if name == 'random':
            return None        # drawn by the caller's generator
        c = colour(name)
        if c is None:
            p = wf.prop(e, 'color')
            wf.warn(p, 'unknown colour "%s"; Stage uses red' % name)
            return DEFAULT_COLOR
        return c
    rgba = wf.read_tuple(e, 'color_rgba', 'ffff')
    return tuple(rgba) if rgba is not None else default


class Model:
    """A Stage model: the tree, the pose, the geometry and the body (blocks)."""

    def __init__(self, world_dir, parent, kind, index, entity, counts):
        self.world_dir = world_dir
        self.parent = parent
        self.kind = kind
        self.index = index
        self.entity = entity
        self.children = []
        self.pose = (0.0, 0.0, 0.0, 0.0)
        self.geom_pose = (0.0, 0.0, 0.0, 0.0)
        self.geom_size = DEFAULT_SIZE
        self.color = DEFAULT_COLOR
        self.blocks = [rect_block(-0.5, -0.5, 1.0, 1.0, 1.0)]
        self.has_default_block = True
        self.boundary = False
        self.stack_children = True
        self.obstacle_return = True
        self.ranger_return = 1.0
        self.interval_us = DEFAULT_INTERVAL_US
        self.ctrl = []
        self.bitmap = None
        scope = parent.child_counts if parent else counts
        n = scope.get(kind, 0)
        scope[kind] = n + 1
        self.token = ('%s.%s:%d' % (parent.token, kind, n)) if parent else '%s:%d' % (kind, n)
        self.name = ''
        self.gui_nose = False
        self.child_counts = {}
        if parent is not None:
            parent.children.append(self)
        self.construct()

    def construct(self):
        """The type's constructor (Model's does nothing more)."""

    def set_geom(self, pose, size):
        self.geom_pose = pose
        self.geom_size = size
        calc_size(self.blocks, size)

    def clear_blocks(self):
        self.blocks = []

    @property
    def root(self):
        m = self
        while m.parent is not None:
            m = m.parent
        return m

    def global_pose(self):
        """Model::GetGlobalPose: (x, y, z, a) in the world."""
        if self.parent is None:
            return self.pose
        x, y, z, a = pose_add(self.parent.global_pose(), self.pose)
        if self.parent.stack_children:
            z += self.parent.geom_size[2]
        return (x, y, z, a)

    def body_pose(self):
        """GetGlobalPose() + geom.pose: the frame of the blocks' points."""
        return pose_add(self.global_pose(), self.geom_pose)

    def pixel_vertices(self, block, ppm, body=None):
        """Model::LocalToPixels of a block at the model's current (or a given body) pose:
        int64 (N,) x and y cells, floor(world coordinate * ppm)."""
        gx, gy, _, ga = self.body_pose() if body is None else body
        cosa = math.cos(ga)
        sina = math.sin(ga)
        x = gx + block.pts[:, 0] * cosa - block.pts[:, 1] * sina
        y = gy + block.pts[:, 0] * sina + block.pts[:, 1] * cosa
        return np.floor(x * ppm).astype(np.int64), np.floor(y * ppm).astype(np.int64)

    def block_z(self, block):
        """Block::Map's global_z of a block: its local z plus the model's global z and
        origin z."""
        gz = self.global_pose()[2] + self.geom_pose[2]
        return block.zmin + gz, block.zmax + gz

    # ---- Model::Load -------------------------------------------------------------------
    def load(self, wf, rng):
        e = self.entity
        for name in ('event_queue', 'watts', 'give_watts', 'take_watts', 'debug', 'mass',
                     'blob_return', 'fiducial_key', 'fiducial_return', 'gripper_return',
                     'gui_nose', 'gui_grid', 'gui_outline', 'gui_move', 'map_resolution',
                     'say', 'trail_length', 'trail_interval', 'alwayson', 'joules',
                     'joules_capacity', 'kjoules', 'kjoules_capacity', 'friction'):
            if wf.exists(e, name):
                wf.read_string(e, name, '')
        self.name = wf.read_string(e, 'name', '')
        # GuiState::Load: a heading mark in the window (drawn by the node's window only)
        self.gui_nose = wf.read_int(e, 'gui_nose', 0) != 0
        pose = read_pose(wf, e, 'origin', self.geom_pose)
        size = tuple(wf.read_tuple(e, 'size', 'lll') or self.geom_size)
        self.set_geom(pose, size)
        self.pose = read_pose(wf, e, 'pose', self.pose)
        c = read_colour(wf, e, self.color)
        self.color = c if c is not None else (rng.random(), rng.random(), rng.random(), 1.0)
        if wf.read_int(e, 'noblocks', 0) and self.has_default_block:
            self.blocks = []
            self.has_default_block = False
            calc_size(self.blocks, self.geom_size)
        if wf.exists(e, 'bitmap'):
            self.load_bitmap(wf, e)
        if wf.exists(e, 'boundary'):
            self.boundary = bool(wf.read_int(e, 'boundary', 0))
            if self.boundary:
                self.add_boundary()
        self.stack_children = bool(wf.read_int(e, 'stack_children', 1))
        self.obstacle_return = bool(wf.read_int(e, 'obstacle_return', 1))
        self.ranger_return = wf.read_float(e, 'ranger_return', self.ranger_return)
        ctrl = wf.read_values(e, 'ctrl')
        if ctrl is not None:
            self.ctrl = ctrl
            wf.warn(wf.prop(e, 'ctrl'), 'ctrl %s: controller plugins are not run here; the model'
                    ' is loaded and nothing drives it' % ' '.join(self.ctrl))
        interval_ms = wf.read_int(e, 'update_interval', self.interval_us // 1000)
        self.interval_us = 1000 * interval_ms
        if self.interval_us <= 0:
            p = wf.prop(e, 'update_interval')
            raise WorldError(p.path, p.line, 'update_interval must be at least 1 ms')
        calc_size(self.blocks, self.geom_size)

    def load_bitmap(self, wf, e):
        p = wf.prop(e, 'bitmap')
        name = wf.read_string(e, 'bitmap', '')
        if self.has_default_block:
            self.blocks = []
            self.has_default_block = False
        path = name if name.startswith('/') else os.path.join(self.world_dir, name)
        try:
            occ = image.occupied(image.first_channel(path))
        except WorldError as err:
            raise WorldError(p.path, p.line, '%s: %s' % (path, err.what)) from None
        polys = image.polygons(occ)
        for pts in polys:
            self.blocks.append(Block(pts, 0.0, 1.0))
        if polys:
            # for pictures and maps: the image and the pixel box the body's size spans
            allp = np.vstack(polys)
            self.bitmap = (occ, float(allp[:, 0].min()), float(allp[:, 0].max()),
                           float(allp[:, 1].min()), float(allp[:, 1].max()))
        calc_size(self.blocks, self.geom_size)

    def add_boundary(self):
        calc_size(self.blocks, self.geom_size)
        minx, maxx, miny, maxy, minz, maxz = bounding_box(self.blocks)
        w = BOUNDARY_WIDTH
        sx, sy, sz = maxx - minx, maxy - miny, maxz - minz
        self.blocks += [rect_block(minx, miny, w, sy, sz), rect_block(minx, miny, sx, w, sz),
                        rect_block(minx, maxy - w, sx, w, sz),
                        rect_block(maxx - w, miny, w, sy, sz)]

    def load_block(self, wf, e):
        """Model::LoadBlock: a `block( points N point[i] [x y] z [zmin zmax] )`."""
        if self.has_default_block:
            self.blocks = []
            self.has_default_block = False
        count = wf.read_int(e, 'points', 0)
        pts = [tuple(wf.read_tuple(e, 'point[%d]' % k, 'll') or (0.0, 0.0))
               for k in range(count)]
        z = wf.read_tuple(e, 'z', 'll') or (0.0, 0.0)
        if len(pts) < 3:
            ent = wf.entities[e]
            raise WorldError(ent.path, ent.line, 'a block needs at least 3 points, got %d'
                             % len(pts))
        self.blocks.append(Block(canonical_winding(pts), z[0], z[1]))


def canonical_winding(pts):
    """block.cc's canonicalize_winding: counter-clockwise (the sum of the turns between
    successive edges, each in (-pi, pi], must be positive), else reversed."""
    n = len(pts)
    vs = [(pts[(i + 1) % n][0] - pts[i][0], pts[(i + 1) % n][1] - pts[i][1]) for i in range(n)]
    total = 0.0
    for i in range(n):
        a1 = math.atan2(vs[i][1], vs[i][0])
        while a1 < 0:
            a1 += 2 * math.pi
        a2 = math.atan2(vs[(i + 1) % n][1], vs[(i + 1) % n][0])
        while a2 < 0:
            a2 += 2 * math.pi
        d = a2 - a1
        while d < -math.pi:
            d += 2 * math.pi
        while math.pi < d:
            d -= 2 * math.pi
        total += d
    return pts if total > 0 else pts[::-1]


class Ranger(Model):
    """ModelRanger: no body of its own, its `sensor( )`s."""

    def construct(self):
        self.color = (0.0, 0.0, 0.5, 1.0)
        self.clear_blocks()
        self.set_geom((0.0, 0.0, 0.0, 0.0), RANGER_SIZE)
        self.sensors = []

    def load_sensor(self, wf, e):
        s = Sensor()
        s.load(wf, e)
        self.sensors.append(s)

    def ray_origin(self, sensor):
        """The first ray's pose (x, y, z, a) in the world, as Sensor::Update makes it: the
        sensor's pose, turned to the first beam, raised to half the transducer's height."""
        x, y, z, a = sensor.pose
        start = -sensor.fov / 2.0 if sensor.samples > 1 else 0.0
        local = (x, y, z + sensor.size[2] / 2.0, a + start)
        return pose_add(self.body_pose(), local)

    @staticmethod
    def sample_increment(sensor):
        return sensor.fov / max(sensor.samples - 1, 1)


class Position(Model):
    """ModelPosition: drive, localisation and velocity bounds; its state lives in the World."""

    def construct(self):
        self.drive = 'diff'
        self.localization = 'gps'
        self.wheelbase = 1.0
        self.velocity_bounds = [(-1.0, 1.0), (-1.0, 1.0), (-1.0, 1.0),
                                (-math.pi / 2.0, math.pi / 2.0)]
        self.initial_velocity = (0.0, 0.0, 0.0, 0.0)
        self.integration_error = None

    def load(self, wf, rng):
        super().load(wf, rng)
        e = self.entity
        v = read_pose(wf, e, 'velocity', None)
        if v is not None:
            self.initial_velocity = v
        if wf.exists(e, 'drive'):
            drive = wf.read_string(e, 'drive', 'diff')
            if drive not in ('diff', 'omni', 'car'):
                wf.warn(wf.prop(e, 'drive'), 'invalid drive "%s" (diff, omni or car); Stage'
                        ' uses "diff"' % drive)
            else:
                self.drive = drive
        self.wheelbase = wf.read_length(e, 'wheelbase', self.wheelbase)
        if wf.exists(e, 'odom'):
            wf.warn(wf.prop(e, 'odom'), 'the odom property is no longer read by Stage;'
                    ' use localization_origin')
        gpose = self.global_pose()
        self.est_origin = read_pose(wf, e, 'localization_origin', gpose)
        err = read_pose(wf, e, 'odom_error', None)
        if err is None:
            err = tuple(rng.random() * m - m / 2.0 for m in INTEGRATION_ERROR_MAX)
        self.integration_error = err
        if wf.exists(e, 'localization'):
            loc = wf.read_string(e, 'localization', 'gps')
            if loc not in ('gps', 'odom'):
                wf.warn(wf.prop(e, 'localization'), 'unknown localization "%s" (gps or odom);'
                        ' Stage keeps "gps"' % loc)
            else:
                self.localization = loc
        wf.read_tuple(e, 'acceleration_bounds', 'llllllaa')
        vb = wf.read_tuple(e, 'velocity_bounds', 'llllllaa')
        if vb is not None:
            self.velocity_bounds = [(vb[0], vb[1]), (vb[2], vb[3]), (vb[4], vb[5]),
                                    (vb[6], vb[7])]

    def initial_estimate(self):
        """est_pose at load: the pose in the localisation origin's frame."""
        gx, gy, _, ga = self.global_pose()
        ox, oy, _, oa = self.est_origin
        cosa = math.cos(oa)
        sina = math.sin(oa)
        dx = gx - ox
        dy = gy - oy
        return (dx * cosa + dy * sina, dy * cosa - dx * sina, 0.0, stage_normalize(ga - oa))


class Fiducial(Model):
    def construct(self):
        self.clear_blocks()
        self.set_geom((0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


class Blobfinder(Model):
    def construct(self):
        self.clear_blocks()


class Camera(Model):
    def construct(self):
        self.set_geom((0.0, 0.0, 0.0, 0.0), CAMERA_SIZE)
        self.color = (0.0, 0.0, 0.0, 1.0)


class Blinkenlight(Model):
    def construct(self):
        self.color = (0.0, 1.0, 0.0, 1.0)
        self.set_geom((0.0, 0.0, 0.0, 0.0), BLINKENLIGHT_SIZE)


CLASSES = {'position': Position, 'ranger': Ranger, 'fiducial': Fiducial,
           'blobfinder': Blobfinder, 'camera': Camera, 'blinkenlight': Blinkenlight}


def new_model(world_dir, parent, kind, index, entity, counts):
    return CLASSES.get(kind, Model)(world_dir, parent, kind, index, entity, counts)


__all__ = ['Model', 'Position', 'Ranger', 'Sensor', 'Block', 'new_model', 'calc_size',
           'BUILTIN_TYPES', 'SIMULATED_TYPES']
