"""A Stage camera's frame: its OpenGL drawing of the 2.5-D world, ray cast per pixel (no rospy).

What ModelCamera::GetFrame draws (model_camera.cc, canvas.cc, blockgroup.cc): the buffers
cleared (colour (0.7, 0.7, 0.8), depth 1.0), Canvas::DrawFloor (a white quad at z = 0 over
the world's extent: the super-regions of 1024 x 1024 cells anything was drawn into, and the
origin), then every model's blocks, each an upright prism (its polygon from zmin to zmax),
flat-shaded in the model's `color` (no lighting), its top a polygon drawn by even-odd over
the contours of the model's blocks. glFrustum(±tan(hfov/2)·near, ±tan(vfov/2)·near, near,
far); the depth read back and turned by PerspectiveCamera::realDistance into the distance
along the view axis (planar depth, not the range along the pixel's ray): a wall square to
the view at d reads d in every pixel; where nothing was drawn within far it reads far.

Here each pixel's ray, through the pixel's centre, meets the prisms' sides and tops and the
floor; the nearest hit at a planar depth in [near, far] gives the depth and the colour
(glFrustum clips what is nearer than near: the ray goes on behind it). Not drawn here:
Stage's half-colour outlines of the blocks' edges (1 px antialiased lines).
"""
import math

import numpy as np

from .jit import njit, prange

CLEAR_RGBA = (0.7, 0.7, 0.8, 1.0)     # Canvas::InitGl's glClearColor
FLOOR_RGBA = (1.0, 1.0, 1.0, 1.0)     # Canvas::DrawFloor's glColor4f
BACKGROUND = -1                       # a pixel's hit: nothing drawn
FLOOR = -2                            # a pixel's hit: the floor
SRBITS = 10                           # region.hh: super-regions of 2^10 cells a side
#: Canvas::DrawFloor's glPolygonOffset(2.0, 2.0): the floor's depth is pushed back by
#: factor x its depth slope per pixel. Measured on the real Stage under Xvfb's Mesa (golden
#: data, test/golden/camera/): a constant 2.375 x the slope (1.1875 x the factor), the units
#: term too small to see; so the floor reads deeper than it lies, and where the push reaches
#: 1.0 it fails the depth test (clear colour).
FLOOR_OFFSET_SLOPES = 2.375
_FLOAT32 = np.float32


def gl_ubyte(c):
    """A colour channel in 0..1 as OpenGL stores it in an 8-bit buffer: the float colour
    x 255, rounded (0.7 -> 178, as read back from the real Stage)."""
    return int(math.floor(float(_FLOAT32(c)) * 255.0 + 0.5))


def gl_rgba(colour):
    return tuple(gl_ubyte(min(max(v, 0.0), 1.0)) for v in colour)


def view_rotation(yaw_deg, pitch_deg):
    """Eye to world: Rz(yaw) Rx(pitch), the inverse of PerspectiveCamera::Draw's
    glRotatef(-pitch, x) glRotatef(-yaw, z); the eye looks along its -z, +y up."""
    y = math.radians(yaw_deg)
    p = math.radians(pitch_deg)
    cy, sy, cp, sp = math.cos(y), math.sin(y), math.cos(p), math.sin(p)
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cp, -sp], [0.0, sp, cp]])
    return rz @ rx


def world_blocks(models, ppm):
    """The models' blocks in world coordinates, for the kernel: (boxes (n, 6) minx maxx miny
    maxy zmin zmax, edge ranges (n, 2), edges (m, 4) x1 y1 x2 y2, block models (n,),
    groups (g, 3) first block, end block, model: a model's consecutive blocks of one height
    range, whose tops are one even-odd polygon, and the cell box (x0, y0, x1, y1) of the
    vertices or None)."""
    boxes, ranges, edges, owners, groups = [], [], [], [], []
    cells = []
    n_edges = 0
    for m in models:
        if not m.blocks:
            continue
        gx, gy, _, ga = m.body_pose()
        cosa, sina = math.cos(ga), math.sin(ga)
        last = None
        for block in m.blocks:
            p = block.pts
            if len(p) < 2:
                continue
            x = gx + p[:, 0] * cosa - p[:, 1] * sina
            y = gy + p[:, 0] * sina + p[:, 1] * cosa
            zmin, zmax = m.block_z(block)
            cells.append((np.floor(x * ppm), np.floor(y * ppm)))
            e = np.empty((len(p), 4))
            e[:, 0], e[:, 1] = x, y
            e[:, 2], e[:, 3] = np.roll(x, -1), np.roll(y, -1)
            edges.append(e)
            k = len(boxes)
            boxes.append((x.min(), x.max(), y.min(), y.max(), zmin, zmax))
            ranges.append((n_edges, n_edges + len(p)))
            n_edges += len(p)
            owners.append(m.index)
            if last == (zmin, zmax) and groups and groups[-1][2] == m.index:
                groups[-1][1] = k + 1
            else:
                groups.append([k, k + 1, m.index])
            last = (zmin, zmax)
    if not boxes:
        return (np.zeros((0, 6)), np.zeros((0, 2), np.int64), np.zeros((0, 4)),
                np.zeros(0, np.int64), np.zeros((0, 3), np.int64), None)
    cx = np.concatenate([c[0] for c in cells])
    cy = np.concatenate([c[1] for c in cells])
    return (np.array(boxes), np.array(ranges, np.int64), np.concatenate(edges),
            np.array(owners, np.int64), np.array(groups, np.int64),
            (int(cx.min()), int(cy.min()), int(cx.max()), int(cy.max())))


class Scene:
    """What Stage's cameras draw: the static blocks once, the moving ones at each frame, the
    models' colours and the floor's extent (which only grows, as World::Extend's)."""

    def __init__(self, models, moving, ppm):
        self.ppm = ppm
        self._moving = [m for m in models if m.index in moving]
        static = world_blocks([m for m in models if m.index not in moving], ppm)
        self._static = static[:5]
        self.rgba = np.array([gl_rgba(m.color) for m in models] or np.zeros((0, 4)),
                             np.uint8).reshape(-1, 4)
        self.floor_rgba = np.array(gl_rgba(FLOOR_RGBA), np.uint8)
        self.clear_rgba = np.array(gl_rgba(CLEAR_RGBA), np.uint8)
        self._cells = [0, 0, 0, 0]     # World::extent starts as the origin
        self._grow(static[5])
        self._frame = None

    def _grow(self, box):
        if box is None:
            return
        c = self._cells
        self._cells = [min(c[0], box[0]), min(c[1], box[1]), max(c[2], box[2]),
                       max(c[3], box[3])]

    def floor_box(self):
        """The floor's (x0, x1, y0, y1), m: World::AddSuperRegion's corners, origin included."""
        x0, y0, x1, y1 = self._cells
        side = 1 << SRBITS
        return np.array([min(0.0, ((x0 >> SRBITS) * side) / self.ppm),
                         max(0.0, (((x1 >> SRBITS) + 1) * side) / self.ppm),
                         min(0.0, ((y0 >> SRBITS) * side) / self.ppm),
                         max(0.0, (((y1 >> SRBITS) + 1) * side) / self.ppm)])

    def refresh(self):
        """The blocks as they stand now (call once per step before rendering)."""
        moving = world_blocks(self._moving, self.ppm)
        self._grow(moving[5])
        sb, sr, se, so, sg = self._static
        mb, mr, me, mo, mg = moving[:5]
        mr = mr + len(se)
        mg = mg.copy()
        mg[:, :2] += len(sb)
        self._frame = (np.concatenate([sb, mb]), np.concatenate([sr, mr]),
                       np.concatenate([se, me]), np.concatenate([so, mo]),
                       np.concatenate([sg, mg]), self.floor_box())

    def render(self, eye_xyz, yaw_deg, pitch_deg, width, height, hfov_deg, vfov_deg, near,
               far):
        """(depth float32 (h, w): planar depth, far where nothing is drawn; hits int64 (h, w):
        model index, FLOOR or BACKGROUND; rgba uint8 (h, w, 4)), row 0 the top."""
        if self._frame is None:
            self.refresh()
        boxes, ranges, edges, owners, groups, floor = self._frame
        rot = view_rotation(yaw_deg, pitch_deg)
        depth = np.empty((height, width), np.float64)
        hits = np.empty((height, width), np.int64)
        cast_pixels(np.array(eye_xyz, np.float64), rot,
                    math.tan(math.radians(hfov_deg) / 2.0),
                    math.tan(math.radians(vfov_deg) / 2.0), near, far,
                    boxes, ranges, edges, owners, groups, floor, depth, hits)
        return depth.astype(np.float32), hits, self.colours(hits)

    def colours(self, hits):
        """The rgba picture of a hit map."""
        table = np.vstack([self.rgba, self.floor_rgba, self.clear_rgba])
        n = len(self.rgba)
        index = np.where(hits >= 0, hits, np.where(hits == FLOOR, n, n + 1))
        return table[index]


@njit(cache=True)
def _inside(px, py, edges, e0, e1):
    """Even-odd: is (px, py) inside the contours edges[e0:e1]?"""
    inside = False
    for e in range(e0, e1):
        x1, y1, x2, y2 = edges[e, 0], edges[e, 1], edges[e, 2], edges[e, 3]
        if (y1 > py) != (y2 > py) and px < x1 + (py - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


@njit(cache=True)
def _box_entry(ox, oy, oz, dx, dy, dz, box, t_lo, t_hi):
    """The ray's entry into the box clipped to [t_lo, t_hi], or -1 if it misses."""
    lo, hi = t_lo, t_hi
    o = (ox, oy, oz)
    d = (dx, dy, dz)
    for a in range(3):
        bmin, bmax = box[2 * a], box[2 * a + 1]
        if d[a] == 0.0:
            if o[a] < bmin or o[a] > bmax:
                return -1.0
        else:
            t1 = (bmin - o[a]) / d[a]
            t2 = (bmax - o[a]) / d[a]
            if t1 > t2:
                t1, t2 = t2, t1
            lo = max(lo, t1)
            hi = min(hi, t2)
            if lo > hi:
                return -1.0
    return lo


@njit(cache=True, parallel=True)
def cast_pixels(eye, rot, tan_h, tan_v, near, far, boxes, ranges, edges, owners, groups,
                floor, depth, hits):
    """Each pixel's nearest hit at planar depth t in [near, far] along eye + t * rot @ (u, v,
    -1) (u, v the pixel centre's tangents; row 0 the top): depth[r, c] = t and hits[r, c] =
    the model, FLOOR, or far and BACKGROUND."""
    height, width = depth.shape
    ox, oy, oz = eye[0], eye[1], eye[2]
    # window depth d = scale (1 - near / t); over the floor plane 1 / t is affine in the
    # pixel's tangents u, v with slopes n_eye.x / -oz, n_eye.y / -oz (n_eye: world up seen
    # from the eye); the push is FLOOR_OFFSET_SLOPES x the larger slope per pixel
    scale = far / (far - near)
    floor_push = 0.0
    if oz > 0.0:
        su = abs(rot[2, 0] / oz) * 2.0 * tan_h / width
        sv = abs(rot[2, 1] / oz) * 2.0 * tan_v / height
        floor_push = FLOOR_OFFSET_SLOPES * scale * near * max(su, sv)
    for r in prange(height):
        v = (1.0 - (r + 0.5) * 2.0 / height) * tan_v
        for c in range(width):
            u = ((c + 0.5) * 2.0 / width - 1.0) * tan_h
            dx = rot[0, 0] * u + rot[0, 1] * v - rot[0, 2]
            dy = rot[1, 0] * u + rot[1, 1] * v - rot[1, 2]
            dz = rot[2, 0] * u + rot[2, 1] * v - rot[2, 2]
            best = far
            hit = BACKGROUND
            for b in range(boxes.shape[0]):
                if _box_entry(ox, oy, oz, dx, dy, dz, boxes[b], near, best) < 0.0:
                    continue
                zmin, zmax = boxes[b, 4], boxes[b, 5]
                for e in range(ranges[b, 0], ranges[b, 1]):
                    ex = edges[e, 2] - edges[e, 0]
                    ey = edges[e, 3] - edges[e, 1]
                    den = dx * ey - dy * ex
                    if den == 0.0:
                        continue
                    wx = edges[e, 0] - ox
                    wy = edges[e, 1] - oy
                    t = (wx * ey - wy * ex) / den
                    if t < near or t > best:
                        continue
                    s = (wx * dy - wy * dx) / den
                    if s < 0.0 or s > 1.0:
                        continue
                    z = oz + t * dz
                    if zmin <= z <= zmax and (t < best or hit == BACKGROUND):
                        best = t
                        hit = owners[b]
            for g in range(groups.shape[0]):
                b0, b1 = groups[g, 0], groups[g, 1]
                zmin, zmax = boxes[b0, 4], boxes[b0, 5]
                if oz > zmax and dz < 0.0:
                    plane = zmax
                elif oz < zmin and dz > 0.0:
                    plane = zmin
                else:
                    continue
                t = (plane - oz) / dz
                if t < near or t >= best:
                    continue
                px, py = ox + t * dx, oy + t * dy
                if _inside(px, py, edges, ranges[b0, 0], ranges[b1 - 1, 1]):
                    best = t
                    hit = groups[g, 2]
            if oz > 0.0 and dz < 0.0:
                t = -oz / dz
                px, py = ox + t * dx, oy + t * dy
                if near <= t <= far and floor[0] <= px <= floor[1] \
                        and floor[2] <= py <= floor[3]:
                    # the floor's window depth pushed back by its polygon offset, against
                    # the nearest block's (or the cleared 1.0)
                    dwin = scale * (1.0 - near / t) + floor_push
                    dbest = scale * (1.0 - near / best) if hit != BACKGROUND else 1.0
                    if dwin < dbest:
                        best = near * far / (far - dwin * (far - near))
                        hit = FLOOR
            depth[r, c] = best
            hits[r, c] = hit
