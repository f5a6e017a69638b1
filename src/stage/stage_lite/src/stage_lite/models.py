"""Models built from world-file entities: bodies, position models (robots) and rangers.

Reads each property Stage 4.3 reads (so the rest draw the "defined but not used" warning),
with Stage's defaults, and turns degrees into radians where Stage does.
"""

import math
import os
from dataclasses import dataclass, field

import numpy as np

from . import bitmap, kinematics
from .worldfile import WorldError

# X11 colours a world is likely to name (from the X11 rgb.txt values); grayN/greyN and
# "#rrggbb" are computed. Stage looks names up in rgb.txt.
X11 = {
    'black': (0, 0, 0), 'white': (255, 255, 255), 'red': (255, 0, 0),
    'green': (0, 255, 0), 'blue': (0, 0, 255), 'yellow': (255, 255, 0),
    'cyan': (0, 255, 255), 'magenta': (255, 0, 255), 'gray': (190, 190, 190),
    'grey': (190, 190, 190), 'orange': (255, 165, 0), 'purple': (160, 32, 240),
    'brown': (165, 42, 42), 'pink': (255, 192, 203), 'violet': (238, 130, 238),
    'navy': (0, 0, 128), 'maroon': (176, 48, 96), 'gold': (255, 215, 0),
    'dark green': (0, 100, 0), 'darkgreen': (0, 100, 0), 'dark blue': (0, 0, 139),
    'darkblue': (0, 0, 139), 'dark red': (139, 0, 0), 'darkred': (139, 0, 0),
    'light blue': (173, 216, 230), 'lightblue': (173, 216, 230), 'light gray': (211, 211, 211),
    'lightgray': (211, 211, 211), 'light grey': (211, 211, 211),
    'lightgrey': (211, 211, 211), 'dark gray': (169, 169, 169), 'darkgray': (169, 169, 169),
    'dark grey': (169, 169, 169), 'darkgrey': (169, 169, 169),
    'orange red': (255, 69, 0), 'orangered': (255, 69, 0), 'tan': (210, 180, 140),
    'khaki': (240, 230, 140), 'turquoise': (64, 224, 208), 'salmon': (250, 128, 114),
    'beige': (245, 245, 220), 'chartreuse': (127, 255, 0), 'coral': (255, 127, 80),
    'forest green': (34, 139, 34), 'forestgreen': (34, 139, 34),
    'sky blue': (135, 206, 235), 'skyblue': (135, 206, 235),
    'steel blue': (70, 130, 180), 'steelblue': (70, 130, 180),
}
DEFAULT_COLOR = (1.0, 0.0, 0.0)     # Stage's model default colour is red

# Stage's defaults
DEFAULT_SIZE = (0.1, 0.1, 0.1)
POSITION_SIZE = (0.4, 0.4, 0.2)     # Stage's position model default body
RANGER_SIZE = (0.15, 0.15, 0.2)
SENSOR_SIZE = (0.02, 0.02, 0.02)    # the beam leaves from half this height
DEFAULT_ODOM_ERROR = (0.03, 0.03, 0.0, 0.05)
DEFAULT_VBOUNDS = (-1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -math.pi / 2, math.pi / 2)

# Properties Stage reads that matter only for its GUI or for devices not simulated here:
# read (no warning) and ignored.
IGNORED = ('gui_nose', 'gui_grid', 'gui_outline', 'gui_move', 'gui_boundary', 'gripper_return',
           'fiducial_return', 'fiducial_key', 'blob_return', 'visionreturn', 'mass',
           'map_resolution', 'stack_children', 'ctrl', 'say', 'alwayson', 'watts',
           'watts_give', 'watts_take', 'watts_k', 'take_watts', 'give_watts', 'update_interval',
           'wavefront_cost', 'draw_gui', 'ranger_return_unused', 'acceleration_bounds',
           'localization_origin', 'velocity', 'velocity_enable', 'charge', 'power_pool',
           'energy_return', 'friction', 'origin_mode', 'blocks', 'token', 'description')


def parse_color(text, where, warnings):
    """(r, g, b) in 0..1 from an X11 name, grayN / greyN, or #rrggbb; unknown: warning and
    Stage's default red."""
    name = text.strip().lower()
    if name in X11:
        return tuple(c / 255.0 for c in X11[name])
    for prefix in ('gray', 'grey'):
        if name.startswith(prefix) and name[len(prefix):].isdigit():
            n = int(name[len(prefix):])
            if n <= 100:
                v = round(n * 2.55) / 255.0
                return (v, v, v)
    if name.startswith('#') and len(name) == 7:
        try:
            return tuple(int(name[i:i + 2], 16) / 255.0 for i in (1, 3, 5))
        except ValueError:
            pass
    warnings.append('%s:%d: unknown colour "%s"; using red' % (where[0], where[1], text))
    return DEFAULT_COLOR


@dataclass
class Model:
    """A body in the world. pose (x, y, z, yaw) is relative to the parent (world for the top
    level); z_range is absolute (children stack on their parent's top)."""

    kind: str
    declared_type: str
    name: str
    color_rgb: tuple
    pose: tuple
    size: tuple
    origin: tuple
    obstacle_return: bool
    ranger_return: float
    z_range: tuple
    parent: object = None
    children: list = field(default_factory=list)
    placement: object = None          # bitmap.Placement for static bitmap / box bodies
    boundary: bool = False
    robot: object = None              # the Robot when this is a position model

    @property
    def type(self):
        return self.kind

    @property
    def height_range(self):
        return self.z_range

    def world_pose(self):
        """(x, y, yaw) of the model in the world (a robot's current pose for position)."""
        if self.robot is not None:
            return self.robot.pose
        x, y, _, a = self.pose
        if self.parent is None:
            return (x, y, a)
        return kinematics.compose(self.parent.world_pose(), (x, y, a))

    def footprint_world(self):
        """4x2 polygon of the body (its box; the bounding box of a bitmap's occupied pixels)."""
        bx, by, ba = kinematics.body_pose(self.world_pose(),
                                          (self.origin[0], self.origin[1], self.origin[3]))
        return kinematics.rect_corners(bx, by, ba, self.size[0], self.size[1])


def _read_common(ent, parent, kind, warnings, default_size):
    for k in IGNORED:
        ent.prop(k)
    pose = ent.tuple('pose', (0.0, 0.0, 0.0, 0.0), angles=(3,))
    size = ent.tuple('size', default_size)
    if min(size) < 0:
        raise ent.error('size', 'size must not be negative, got %s' % (size,))
    origin = ent.tuple('origin', (0.0, 0.0, 0.0, 0.0), angles=(3,))
    if ent.has('color_rgba'):
        rgba = ent.tuple('color_rgba', (1.0, 0.0, 0.0, 1.0))
        color = tuple(min(max(c, 0.0), 1.0) for c in rgba[:3])
        ent.prop('color')
    elif ent.has('color'):
        color = parse_color(ent.text('color', 'red'), ent.where('color'), warnings)
    else:
        color = parent.color_rgb if parent is not None else DEFAULT_COLOR
    name = ent.text('name', '')
    obstacle = ent.number('obstacle_return', 1.0) != 0
    ranger_return = ent.number('ranger_return', 1.0)
    base = parent.z_range[1] if parent is not None else 0.0
    z0 = base + pose[2]
    return Model(kind, ent.declared, name, color, pose, size, origin, obstacle, ranger_return,
                 (z0, z0 + size[2]), parent)


@dataclass
class Ranger:
    """One ranger (its first sensor) as stageros publishes it. pose: (x, y, z, yaw) in the
    robot frame, z = body height + the ranger's own z; beam_z: absolute beam height."""

    model: Model
    pose: tuple
    range_min: float
    range_max: float
    fov_rad: float
    samples: int
    noise: tuple
    beam_z: float
    ranges: np.ndarray = None
    intensities: np.ndarray = None

    @property
    def angle_min(self):
        return -self.fov_rad / 2.0

    @property
    def angle_max(self):
        return self.fov_rad / 2.0

    @property
    def angle_increment(self):
        return self.fov_rad / (self.samples - 1) if self.samples > 1 else 0.0

    def local_angles(self):
        return self.angle_min + np.arange(self.samples) * self.angle_increment


def read_ranger(ent, model, robot_height, warnings):
    """The Ranger of a ranger model: its first `sensor( )` block (stageros uses only that)."""
    sensors = [c for c in ent.children if c.kind == 'sensor']
    if not sensors:
        warnings.append('%s:%d: ranger has no sensor( ) block; using range [0 5], 1 sample'
                        % (ent.path, ent.line))
    if len(sensors) > 1:
        warnings.append('%s:%d: ranger has %d sensors; only the first is simulated'
                        % (ent.path, ent.line, len(sensors)))
    s = sensors[0] if sensors else None
    rng = s.tuple('range', (0.0, 5.0)) if s else (0.0, 5.0)
    fov = s.number('fov', 0.0) if s else 0.0
    fov = math.radians(fov)
    samples = s.number('samples', 1.0) if s else 1.0
    noise = s.tuple('noise', (0.0, 0.0, 0.0), angles=(2,)) if s else (0.0, 0.0, 0.0)
    spose = s.tuple('pose', (0.0, 0.0, 0.0, 0.0), angles=(3,)) if s else (0.0,) * 4
    ssize = s.tuple('size', SENSOR_SIZE) if s else SENSOR_SIZE
    if s:
        for k in ('color', 'color_rgba', 'resolution'):
            s.prop(k)
    where = s if s else ent
    if samples < 1 or samples != int(samples):
        raise where.error('samples', 'samples must be a positive whole number, got %s'
                          % samples)
    if not 0 <= rng[0] < rng[1]:
        raise where.error('range', 'range needs 0 <= min < max, got [%s %s]' % rng)
    if not 0 <= fov <= 2 * math.pi + 1e-9:
        raise where.error('fov', 'fov must be within [0 360] degrees')
    mx, my, mz, ma = model.pose
    x, y, a = kinematics.compose((mx, my, ma), (spose[0], spose[1], spose[3]))
    z = robot_height + mz + spose[2]
    beam_z = model.z_range[0] + spose[2] + ssize[2] / 2.0
    r = Ranger(model, (x, y, z, a), rng[0], rng[1], fov, int(samples), noise, beam_z)
    r.ranges = np.full(r.samples, r.range_max, np.float32)
    r.intensities = np.zeros(r.samples, np.float32)
    return r


def read_position(ent):
    """drive, localization, odom_error, velocity bounds (xmin xmax ymin ymax amin amax)."""
    drive = ent.text('drive', 'diff')
    if drive not in ('diff', 'omni', 'car'):
        raise ent.error('drive', 'drive must be "diff", "omni" or "car", got "%s"' % drive)
    loc = ent.text('localization', 'gps')
    if loc not in ('gps', 'odom'):
        raise ent.error('localization', 'localization must be "gps" or "odom", got "%s"' % loc)
    odom_error = ent.tuple('odom_error', DEFAULT_ODOM_ERROR)
    vb = ent.tuple('velocity_bounds', DEFAULT_VBOUNDS, angles=(6, 7))
    bounds = (vb[0], vb[1], vb[2], vb[3], vb[6], vb[7])
    for lo, hi in zip(bounds[::2], bounds[1::2], strict=True):
        if lo > hi:
            raise ent.error('velocity_bounds', 'velocity_bounds needs each min <= max')
    return drive, loc, odom_error, bounds


def read_placement(ent, model, base_dir):
    """Placement of a static body: its bitmap, or a filled box of its size."""
    bmp = ent.text('bitmap', '')
    x, y, _, a = model.pose
    bx, by, ba = kinematics.body_pose((x, y, a), (model.origin[0], model.origin[1],
                                                   model.origin[3]))
    if bmp:
        path = os.path.normpath(os.path.join(base_dir, bmp))
        try:
            occ = bitmap.load_image(path)
        except WorldError as e:
            p = ent.props['bitmap']
            raise WorldError(p.path, p.line, '%s: %s' % (path, e.what)) from None
    else:
        occ = np.ones((1, 1), bool)
    return bitmap.Placement.of(occ, model.size[0], model.size[1], bx, by, ba)
