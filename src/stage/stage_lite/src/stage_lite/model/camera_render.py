"""A Stage camera's frame: its OpenGL drawing of the 2.5-D world, ray cast per pixel (no rospy).

What ModelCamera::GetFrame draws (model_camera.cc, canvas.cc, blockgroup.cc): the buffers
cleared (colour (0.7, 0.7, 0.8), depth 1.0), Canvas::DrawFloor (a white quad at z = 0 over
the world's extent: the super-regions of 1024 x 1024 cells anything was drawn into, and the
origin) with glPolygonOffset(2, 2), then every model's blocks with glPolygonOffset(0.5, 0.5),
each an upright prism (its polygon from zmin to zmax), flat-shaded in the model's `color` (no
lighting), its top a polygon drawn by even-odd over the contours of the model's blocks; depth
test GL_LESS. glFrustum(+-tan(hfov/2) near, +-tan(vfov/2) near, near, far); the depth read
back and turned by PerspectiveCamera::realDistance into the distance along the view axis
(planar depth, not the range along the pixel's ray): a wall square to the view at d reads d
in every pixel; where nothing was drawn within far it reads far.

Here each pixel's ray, through its sample point (SAMPLE_X, SAMPLE_Y: not the centre, see
there), meets the prisms' sides and tops and the floor. Each surface hit at a planar depth in
[near, far] (glFrustum's clipping: the ray goes on behind what is nearer) has a window depth,
pushed back by its polygon offset (factor x its window-depth slope per pixel); the least
wins, below the cleared 1.0, and gives the colour and the depth (realDistance of the pushed
window depth, as Stage reads it). Stage's half-colour outlines of the blocks' edges are not
drawn: no frame of the real Stage shows them (test/golden/camera/README.md).
"""
import math

import numpy as np

from .jit import kernel, njit, prange

CLEAR_RGBA = (0.7, 0.7, 0.8, 1.0)     # Canvas::InitGl's glClearColor
FLOOR_RGBA = (1.0, 1.0, 1.0, 1.0)     # Canvas::DrawFloor's glColor4f
BACKGROUND = -1                       # a pixel's hit: nothing drawn
FLOOR = -2                            # a pixel's hit: the floor
SRBITS = 10                           # region.hh: super-regions of 2^10 cells a side
#: glPolygonOffset's factors (Canvas::DrawFloor's 2.0, BlockGroup::BuildDisplayList's 0.5):
#: a polygon's window depth is pushed back by factor x its largest depth slope per pixel
#: (its units term, a few 2^-24 steps of the depth buffer, is too small to see). So the floor
#: reads deeper than it lies, and where its push reaches 1.0 it fails the depth test.
FLOOR_OFFSET_FACTOR = 2.0
BLOCK_OFFSET_FACTOR = 0.5
#: Where in its pixel the real Stage samples, from the pixel's top-left corner in the image
#: stageros publishes (x right, y down), in pixels. Canvas asks FLTK for a multisample visual
#: (FL_MULTISAMPLE); under Xvfb, Mesa gives it 4 samples per pixel at the standard positions,
#: and the depth and colour read back are sample 0's, at (0.375, 0.125): measured on four
#: frames of the real Stage (test/golden/camera/), where the pixel centre (0.5, 0.5) puts a
#: wall's edges a row off. (A visual without multisampling would sample the centre.)
SAMPLE_X = 0.375
SAMPLE_Y = 0.125
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


@kernel
def _inside(px, py, edges, e0, e1):
    """Even-odd: is (px, py) inside the contours edges[e0:e1]?"""
    inside = False
    for e in range(e0, e1):
        x1, y1, x2, y2 = edges[e, 0], edges[e, 1], edges[e, 2], edges[e, 3]
        if (y1 > py) != (y2 > py) and px < x1 + (py - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


@kernel
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


@kernel
def _push(factor, rot, nx, ny, nz, h, scale_near, du, dv):
    """The polygon offset of a plane n . (p - eye) = h (n in the world, h its signed distance
    from the eye): factor x the larger of its window-depth slopes per column and per row.
    Window depth is scale (1 - near / t) and 1 / t over the plane is affine in the pixel's
    tangents u, v with slopes n_eye.x / h and n_eye.y / h (n_eye: n seen from the eye)."""
    if h == 0.0:
        return 0.0
    ex = rot[0, 0] * nx + rot[1, 0] * ny + rot[2, 0] * nz
    ey = rot[0, 1] * nx + rot[1, 1] * ny + rot[2, 1] * nz
    return factor * scale_near * max(abs(ex / h) * du, abs(ey / h) * dv)


@njit(cache=True, parallel=True)
def cast_pixels(eye, rot, tan_h, tan_v, near, far, boxes, ranges, edges, owners, groups,
                floor, depth, hits):
    """Each pixel's nearest surface along eye + t * rot @ (u, v, -1) (u, v the tangents of
    the pixel's sample point, row 0 the top; t the planar depth, clipped to [near, far]) by
    window depth with its polygon offset: depth[r, c] = realDistance of that window depth and
    hits[r, c] = the model or FLOOR; far and BACKGROUND where nothing is drawn."""
    height, width = depth.shape
    ox, oy, oz = eye[0], eye[1], eye[2]
    scale = far / (far - near)
    scale_near = scale * near
    du = 2.0 * tan_h / width       # tangent per column and per row
    dv = 2.0 * tan_v / height
    floor_push = _push(FLOOR_OFFSET_FACTOR, rot, 0.0, 0.0, 1.0, -oz, scale_near, du, dv)
    for r in prange(height):
        v = tan_v - (r + SAMPLE_Y) * dv
        for c in range(width):
            u = (c + SAMPLE_X) * du - tan_h
            dx = rot[0, 0] * u + rot[0, 1] * v - rot[0, 2]
            dy = rot[1, 0] * u + rot[1, 1] * v - rot[1, 2]
            dz = rot[2, 0] * u + rot[2, 1] * v - rot[2, 2]
            best = 1.0           # the cleared window depth; GL_LESS: the first drawn wins ties
            hit = BACKGROUND
            if oz > 0.0 and dz < 0.0:          # the floor, drawn first
                t = -oz / dz
                px, py = ox + t * dx, oy + t * dy
                if near <= t <= far and floor[0] <= px <= floor[1] \
                        and floor[2] <= py <= floor[3]:
                    w = scale * (1.0 - near / t) + floor_push
                    if w < best:
                        best = w
                        hit = FLOOR
            for b in range(boxes.shape[0]):
                # no surface of the box can win beyond the planar depth whose window depth
                # (unpushed) is best
                t_lim = far if best >= scale else min(far, near / (1.0 - best / scale))
                if _box_entry(ox, oy, oz, dx, dy, dz, boxes[b], near, t_lim) < 0.0:
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
                    if t < near or t > far:
                        continue
                    s = (wx * dy - wy * dx) / den
                    if s < 0.0 or s > 1.0:
                        continue
                    z = oz + t * dz
                    if zmin <= z <= zmax:
                        # the side's plane: normal (ey, -ex, 0), through the edge's start
                        w = scale * (1.0 - near / t) + _push(
                            BLOCK_OFFSET_FACTOR, rot, ey, -ex, 0.0, ey * wx - ex * wy,
                            scale_near, du, dv)
                        if w < best:
                            best = w
                            hit = owners[b]
            for g in range(groups.shape[0]):
                b0, b1 = groups[g, 0], groups[g, 1]
                plane = boxes[b0, 5]     # Stage draws a top, no bottom, seen from either side
                if dz == 0.0:
                    continue
                t = (plane - oz) / dz
                if t < near or t > far:
                    continue
                w = scale * (1.0 - near / t) + _push(BLOCK_OFFSET_FACTOR, rot, 0.0, 0.0, 1.0,
                                                     plane - oz, scale_near, du, dv)
                if w >= best:
                    continue
                px, py = ox + t * dx, oy + t * dy
                if _inside(px, py, edges, ranges[b0, 0], ranges[b1 - 1, 1]):
                    best = w
                    hit = groups[g, 2]
            depth[r, c] = near * far / (far - best * (far - near))
            hits[r, c] = hit
