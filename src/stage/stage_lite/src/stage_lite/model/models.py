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
The blocks' geometry (CalcSize, the bounding box, winding) is bodies.py's; the ranger's and
the position model's own properties are read in ranger.py and position.py.
"""
import math
import os

import numpy as np

from . import grid, image
from .bodies import Block, bounding_box, calc_size, canonical_winding, rect_block
from .energy import load_energy
from .pose import pose_add, stage_normalize
from .worldfile import WorldError

DEFAULT_SIZE = (0.4, 0.4, 1.0)        # Stage's Size()
BLINKENLIGHT_SIZE = (0.02, 0.02, 0.02)
BOUNDARY_WIDTH = 0.01                 # Model::Load's boundary rectangles, m
DEFAULT_INTERVAL_US = 100000
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


def read_pose(wf, e, name, default):
    """Pose::Load: four values (x, y, z, angle) as written; default if absent. The angle is
    not normalised: Stage's Load calls normalize(a) and drops what it returns (a sensor at
    330 degrees keeps 330 degrees, whose cosine and sine differ from -30's in the last
    bit); only Model::SetPose normalises (set_pose_as_loaded)."""
    v = wf.read_tuple(e, name, 'llla')
    if v is None:
        return default
    return (v[0], v[1], v[2], v[3])


def set_pose_as_loaded(current, loaded):
    """Model::Load's SetPose(loaded): a pose that differs from the current one, with its
    angle normalised (Stage leaves an equal one as it is)."""
    if loaded == current:
        return current
    return (loaded[0], loaded[1], loaded[2], stage_normalize(loaded[3]))


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


def random_colour(rand48):
    """`color "random"`, as Stage draws it: Model::Load makes Color(drand48(), drand48(),
    drand48()), then Color::Load reads the same property and draws r, g and b again; six
    drand48() draws (rand48: glibc_random.Rand48), the last three the colour."""
    for _ in range(3):
        rand48.drand48()
    r = rand48.drand48()
    g = rand48.drand48()
    b = rand48.drand48()
    return (r, g, b, 1.0)


class Model:
    """A Stage model: the tree, the pose, the geometry and the body (blocks)."""

    #: Stage runs a thread-safe model's updates in a worker thread (rangers, fiducial
    #: finders, bumpers): its queue is drawn from random() when it starts
    THREAD_SAFE_KINDS = ('ranger', 'fiducial', 'bumper')

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
        # Model::Visibility's, for the fiducial finders and blobfinders (fiducial.py)
        self.fiducial_return = 0
        self.fiducial_key = 0
        self.blob_return = True
        self.interval_us = DEFAULT_INTERVAL_US
        self.ctrl = []           # [(the ctrl string, world file, line)]
        self.bitmap = None
        self.flags = []          # the flags it carries (Stage's flag_list), the top last
        self.used = False        # taken by GetUnusedModelOfType
        self.alwayson = False    # Stage subscribes it as it loads (`alwayson 1`)
        # the energy model's (energy.py): its own pack, what it draws, gives and takes, kg
        self.power_pack = None
        self.watts = 0.0
        self.watts_give = 0.0
        self.watts_take = 0.0
        self.mass = 0.0
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
    def thread_safe(self):
        return self.kind in self.THREAD_SAFE_KINDS

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

    def outline_cells(self, block, ppm):
        """Stage's MapPoly of a block at the model's current pose: the (x, y) int64 cells
        of its outline."""
        vx, vy = self.pixel_vertices(block, ppm)
        n = grid.poly_cell_count(vx, vy)
        xs = np.empty(n, np.int64)
        ys = np.empty(n, np.int64)
        grid.poly_cells(vx, vy, xs, ys, 0)
        return xs, ys

    def block_z(self, block):
        """Block::Map's global_z of a block: its local z plus the model's global z and
        origin z."""
        gz = self.global_pose()[2] + self.geom_pose[2]
        return block.zmin + gz, block.zmax + gz

    # ---- Model::Load -------------------------------------------------------------------
    def load(self, wf, rand48):
        e = self.entity
        for name in ('event_queue', 'debug', 'gripper_return',
                     'gui_nose', 'gui_grid', 'gui_outline', 'gui_move', 'map_resolution',
                     'say', 'trail_length', 'trail_interval', 'friction'):
            if wf.exists(e, name):
                wf.read_string(e, name, '')
        load_energy(self, wf, e)
        self.alwayson = bool(wf.read_int(e, 'alwayson', 0))   # subscribed at load (World)
        self.name = wf.read_string(e, 'name', '')
        if self.name:
            self.token = self.name    # Stage's token: its children's names start with it
        # GuiState::Load: a heading mark in the window (drawn by the node's window only)
        self.gui_nose = wf.read_int(e, 'gui_nose', 0) != 0
        pose = read_pose(wf, e, 'origin', self.geom_pose)
        size = tuple(wf.read_tuple(e, 'size', 'lll') or self.geom_size)
        self.set_geom(pose, size)
        self.pose = set_pose_as_loaded(self.pose, read_pose(wf, e, 'pose', self.pose))
        c = read_colour(wf, e, self.color)
        self.color = c if c is not None else random_colour(rand48)
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
        self.blob_return = wf.read_int(e, 'blob_return', int(self.blob_return)) != 0
        self.fiducial_key = wf.read_int(e, 'fiducial_key', self.fiducial_key)
        self.fiducial_return = wf.read_int(e, 'fiducial_return', self.fiducial_return)
        ctrl = wf.read_values(e, 'ctrl')
        if ctrl is not None:
            # each value is one controller, "name args" (controllers.py starts them)
            p = wf.prop(e, 'ctrl')
            self.ctrl = [(value, p.path, p.line) for value in ctrl]
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


class Fiducial(Model):
    def construct(self):
        self.clear_blocks()
        self.set_geom((0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


class Blobfinder(Model):
    def construct(self):
        self.clear_blocks()


class Blinkenlight(Model):
    def construct(self):
        self.color = (0.0, 1.0, 0.0, 1.0)
        self.set_geom((0.0, 0.0, 0.0, 0.0), BLINKENLIGHT_SIZE)
