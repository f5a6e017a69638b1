"""Stage 4.3's blobfinder (libstage/model_blobfinder.cc), rule for rule (no rospy).

A `blobfinder` model sees colour blobs in a one-row scan. Its properties, as
ModelBlobfinder::Load reads them, with Stage's defaults:
- `image [w h]` (80 60): the image's width (the scan's rays) and height, in pixels;
- `range` (12.0; read as a plain number, not a length: `unit_length` does not apply);
- `fov` (degrees, 60) and `pan` (degrees, 0: the scan's middle, from the model's heading);
- `colors_count` N and `colors [ "name" ... ]`: the channels' colours, the first N names (a
  list shorter than N: Stage exits); read only when `colors` is there. With no colour every
  blob is reported, whatever its colour.
Its body: none (Stage's ClearBlocks; size stays the model default).

An update (ModelBlobfinder::Update):
1. w rays from the model's global pose + origin, turned by pan: ray s (0 = the rightmost) at
   s * fov / (w - 1) - (fov / 2 - heading), each `range` m long, stopping at the first block
   of any model not related to the finder, at any height (no z test; ranger_return,
   obstacle_return and blob_return play no part: sight.py); a ray's colour is its model's;
2. from s = 0, a blob starts at a ray that hit something and runs while the rays hit models
   of the same colour (r, g, b within 1e-5; alpha ignored); the ray after a blob is skipped
   whatever it hit (STAGE_BLOB_SKIPS_NEXT_RAY: the scan's for loop steps past it);
3. a blob whose colour is none of the channels' (when there are channels) is dropped; else:
   range = the mean of its rays' ranges; its rows from a 0.6 m tall target at that range:
   top = h / 2 - int(atan2(0.3, range) / (fov / h)) (at least 0), bottom = h / 2 + the same
   (at most h); its columns mirrored (the image's x grows to the left of the scan):
   left = w - 1 - its last ray, right = w - 1 - its first.

What it needs from the world: a sight.Sight (world.models, .robots, .space) and the layer a
step's rays read ((world.updates + 1) % 2 during a step): blobfinder.update(sight, layer).
Stage runs it in the main thread (not thread_safe), before the step's moves.
"""
import math
from dataclasses import dataclass

import numpy as np

from . import models
from .models import colour
from .pose import pose_add
from .worldfile import WorldError

DEFAULT_RANGE = 12.0             # m
DEFAULT_FOV = math.pi / 3.0      # rad
DEFAULT_PAN = 0.0                # rad
DEFAULT_IMAGE = (80, 60)         # pixels: scan width, scan height
TARGET_HEIGHT = 0.6              # m: Stage's robotHeight, every blob's assumed height
COLOUR_EPSILON = 1e-5            # ColorMatchIgnoreAlpha
INT_MIN = -(1 << 31)             # x86's conversion of NaN or an out-of-range double to int


@dataclass(frozen=True)
class Blob:
    """One blob, as Stage's ModelBlobfinder::Blob holds it (pixels as uint32)."""

    color: tuple      # (r, g, b, a) in 0..1: the colour of the models its rays hit
    left: int
    top: int
    right: int
    bottom: int
    range: float      # m: the mean range of its rays


def colour_match(a, b):
    """ColorMatchIgnoreAlpha."""
    return all(abs(a[k] - b[k]) < COLOUR_EPSILON for k in range(3))


def _c_int(x):
    """C's (int) of a double as x86 does it (NaN and out of range: INT_MIN)."""
    if not math.isfinite(x) or not INT_MIN <= x < -INT_MIN:
        return INT_MIN
    return int(x)


def _int32(v):
    """An int wrapped to int32, as C's unsigned arithmetic stored into an int."""
    return (v + (1 << 31)) % (1 << 32) - (1 << 31)


def _c_divide(a, b):
    """a / b in IEEE doubles (b = 0 gives +-inf or NaN, as in C)."""
    with np.errstate(divide='ignore', invalid='ignore'):
        return float(np.float64(a) / np.float64(b))


class Blobfinder(models.Blobfinder):
    """ModelBlobfinder: its properties and its blobs (`blobs`, left to right in the scan)."""

    thread_safe = False      # Stage updates it in the main thread

    def construct(self):
        super().construct()
        self.colors = []
        self.range = DEFAULT_RANGE
        self.fov = DEFAULT_FOV
        self.pan = DEFAULT_PAN
        self.scan_width, self.scan_height = DEFAULT_IMAGE
        self.blobs = []

    def load(self, wf, rand48):
        """ModelBlobfinder::Load: Model::Load, then the blobfinder's own properties."""
        super().load(wf, rand48)
        e = self.entity
        image = wf.read_tuple(e, 'image', 'ii')
        if image is not None:
            if min(image) < 0:
                p = wf.prop(e, 'image')
                raise WorldError(p.path, p.line, 'image [%d %d]: a size must be >= 0 (Stage'
                                 ' reads it unsigned: billions of rays)' % tuple(image))
            self.scan_width, self.scan_height = image
        self.range = wf.read_float(e, 'range', self.range)
        self.fov = wf.read_angle(e, 'fov', self.fov)
        self.pan = wf.read_angle(e, 'pan', self.pan)
        if wf.exists(e, 'colors'):
            count = wf.read_int(e, 'colors_count', 0) % (1 << 32)   # read as unsigned
            names = wf.read_values(e, 'colors')
            if count > len(names):
                p = wf.prop(e, 'colors')
                raise WorldError(p.path, p.line, 'colors has %d names, colors_count says %d'
                                 ' (Stage exits: "reading tuple colors index %d")'
                                 % (len(names), count, len(names)))
            self.colors = [colour(name) or models.DEFAULT_COLOR for name in names[:count]]

    def ray_angles(self):
        """The scan's rays: (origin (x, y, z, a) in the world, each ray's angle)."""
        origin = pose_add(self.body_pose(), (0.0, 0.0, 0.0, self.pan))
        w = self.scan_width
        starta = self.fov / 2.0 - origin[3]
        if w == 1:
            # 0 * fov / 0.0 is NaN in Stage, and a ray at a NaN angle walks no cell
            return origin, [math.nan]
        return origin, [(s * self.fov / float(w - 1)) - starta for s in range(w)]

    def scan(self, sight, layer):
        """The scan's rays: (ranges m, models hit or -1), the first ray the rightmost."""
        origin, angles = self.ray_angles()
        if angles and math.isnan(angles[0]):
            return np.array([self.range]), np.array([-1])
        return sight.cast(origin, angles, self.range, self, False, layer)

    def update(self, sight, layer):
        """ModelBlobfinder::Update: the blobs (self.blobs, also returned) seen through the
        grid's `layer`."""
        ranges, hits = self.scan(sight, layer)
        seen = sight.models
        w, h = self.scan_width, self.scan_height
        y_rad_per_pixel = _c_divide(self.fov, h)
        self.blobs = []
        s = 0
        while s < w:
            if hits[s] < 0:
                s += 1
                continue
            right = s
            col = seen[hits[s]].color
            while s < w and hits[s] >= 0 and colour_match(seen[hits[s]].color, col):
                s += 1
            left = s - 1
            s += 1                  # STAGE_BLOB_SKIPS_NEXT_RAY
            if self.colors and not any(colour_match(col, c) for c in self.colors):
                continue
            rng = 0.0
            for t in range(right, left + 1):
                rng += float(ranges[t])
            rng /= left - right + 1
            start = math.atan2(TARGET_HEIGHT / 2.0, rng)
            top = max(_int32(h // 2 - _c_int(_c_divide(start, y_rad_per_pixel))), 0)
            bottom = min(_int32(h // 2 - _c_int(_c_divide(-start, y_rad_per_pixel))), h)
            self.blobs.append(Blob(color=col, left=w - left - 1, top=top % (1 << 32),
                                   right=w - right - 1, bottom=bottom % (1 << 32), range=rng))
        return self.blobs
