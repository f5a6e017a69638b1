"""Floor-plan bitmaps: PGM (P5, P2) and PNG read into an occupancy image and drawn onto the
world grid the way Stage 4 places them.

Stage's rules: a pixel is an obstacle when its value is <= 127; the image's y axis points
down; the bounding box of the OCCUPIED pixels (not the whole image) is scaled to the model's
`size`, centred on its pose (plus `origin`) and rotated by its yaw; `boundary 1` adds thin walls
round that box. A grid cell is occupied when its centre falls in an occupied pixel (cells
smaller than pixels), or when any of k x k sample points does (pixels smaller than cells).
"""

import math
from dataclasses import dataclass

import numpy as np

from .worldfile import WorldError

OCCUPIED_MAX = 127     # Stage: a pixel value <= 127 (of 255) is an obstacle
ROW_CHUNK = 256        # grid rows per chunk in the rotated path (bounds temporary memory)


@dataclass(frozen=True)
class GridSpec:
    """The world grid: cell (row, col) covers [ox + col*res, +res) x [oy + row*res, +res)."""

    origin_x: float
    origin_y: float
    resolution: float
    rows: int
    cols: int

    @staticmethod
    def covering(xmin, ymin, xmax, ymax, resolution, pad_cells=2):
        """A grid aligned to multiples of `resolution` (as Stage's is) holding the box."""
        c0 = math.floor(xmin / resolution + 1e-9) - pad_cells
        r0 = math.floor(ymin / resolution + 1e-9) - pad_cells
        c1 = math.ceil(xmax / resolution - 1e-9) + pad_cells
        r1 = math.ceil(ymax / resolution - 1e-9) + pad_cells
        return GridSpec(c0 * resolution, r0 * resolution, resolution,
                        max(1, r1 - r0), max(1, c1 - c0))


def _read_pgm(data, path):
    """(H, W) uint8-scaled-to-255 array from P5 or P2 bytes."""
    magic = data[:2]
    fields = []
    i = 2
    n = len(data)
    need = 3
    while len(fields) < need:
        while i < n and data[i:i + 1].isspace():
            i += 1
        if i < n and data[i:i + 1] == b'#':
            while i < n and data[i:i + 1] not in (b'\n', b'\r'):
                i += 1
            continue
        j = i
        while j < n and not data[j:j + 1].isspace() and data[j:j + 1] != b'#':
            j += 1
        if j == i:
            raise WorldError(path, None, 'not a valid PGM image (truncated header)')
        fields.append(data[i:j])
        i = j
    try:
        w, h, maxval = (int(f) for f in fields)
    except ValueError:
        raise WorldError(path, None, 'not a valid PGM image (bad header)') from None
    if w <= 0 or h <= 0 or not 0 < maxval < 65536:
        raise WorldError(path, None, 'not a valid PGM image (size %dx%d, maxval %d)'
                         % (w, h, maxval))
    if magic == b'P5':
        i += 1      # exactly one white-space byte ends the header
        dtype = np.dtype('>u2') if maxval > 255 else np.dtype(np.uint8)
        count = w * h
        body = data[i:i + count * dtype.itemsize]
        if len(body) < count * dtype.itemsize:
            raise WorldError(path, None, 'not a valid PGM image (truncated pixel data)')
        raw = np.frombuffer(body, dtype=dtype, count=count)
    else:
        try:
            raw = np.array(data[i:].split()[:w * h], dtype=np.int64)
        except ValueError:
            raise WorldError(path, None, 'not a valid PGM image (bad pixel value)') from None
        if raw.size < w * h:
            raise WorldError(path, None, 'not a valid PGM image (truncated pixel data)')
    img = raw.reshape(h, w).astype(np.float32) * (255.0 / maxval)
    return img


def load_image(path):
    """Occupancy of an image file: bool (H, W), row 0 = top of the picture; WorldError if the
    file is missing or not an image."""
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except FileNotFoundError:
        raise WorldError(path, None, 'bitmap file does not exist') from None
    except OSError as e:
        raise WorldError(path, None, 'cannot read bitmap: %s' % e.strerror) from None
    if data[:2] in (b'P5', b'P2'):
        img = _read_pgm(data, path)
        return img <= OCCUPIED_MAX
    try:
        import io

        from PIL import Image
        with Image.open(io.BytesIO(data)) as im:
            if im.mode in ('RGBA', 'LA', 'PA') or 'transparency' in im.info:
                # transparent pixels count as free floor (white)
                im = im.convert('RGBA')
                bg = Image.new('RGBA', im.size, (255, 255, 255, 255))
                im = Image.alpha_composite(bg, im)
            grey = np.asarray(im.convert('L'))
    except ImportError:
        raise WorldError(path, None, 'PNG bitmaps need python3-pil') from None
    except Exception:
        raise WorldError(path, None, 'not an image (PGM or PNG expected)') from None
    return grey <= OCCUPIED_MAX


@dataclass(frozen=True)
class Placement:
    """Where a bitmap lands: the centre and yaw of its box, the box size, the occupied crop."""

    cx: float
    cy: float
    yaw: float
    size_x: float
    size_y: float
    occ: np.ndarray        # the bounding-box crop of the occupancy, row 0 = top

    @staticmethod
    def of(occ, size_x, size_y, cx, cy, yaw):
        rows = np.flatnonzero(occ.any(axis=1))
        cols = np.flatnonzero(occ.any(axis=0))
        if rows.size == 0:
            crop = np.zeros((1, 1), bool)
        else:
            crop = occ[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]
        return Placement(cx, cy, yaw, size_x, size_y, crop)

    def corners(self):
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        hx, hy = self.size_x / 2, self.size_y / 2
        return np.array([(self.cx + c * u - s * v, self.cy + s * u + c * v)
                         for u, v in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))])


def rasterise(pl, grid, boundary=False):
    """Bool mask of `grid` cells the placed bitmap occupies."""
    out = np.zeros((grid.rows, grid.cols), bool)
    cr = pl.corners()
    res = grid.resolution
    c0 = max(0, math.floor((cr[:, 0].min() - grid.origin_x) / res) - 1)
    c1 = min(grid.cols, math.ceil((cr[:, 0].max() - grid.origin_x) / res) + 1)
    r0 = max(0, math.floor((cr[:, 1].min() - grid.origin_y) / res) - 1)
    r1 = min(grid.rows, math.ceil((cr[:, 1].max() - grid.origin_y) / res) + 1)
    if c0 >= c1 or r0 >= r1:
        return out
    h, w = pl.occ.shape
    pw, ph = pl.size_x / w, pl.size_y / h
    k = max(1, math.ceil(res / min(pw, ph) - 1e-9))
    offs = (np.arange(k) + 0.5) / k * res
    # padded with one free row and column so out-of-box indices (-1) read free floor
    padded = np.zeros((h + 1, w + 1), bool)
    padded[:h, :w] = pl.occ
    quarter = pl.yaw / (math.pi / 2)
    gx0 = grid.origin_x + np.arange(c0, c1) * res
    gy0 = grid.origin_y + np.arange(r0, r1) * res
    if abs(quarter - round(quarter)) < 1e-9:
        q = int(round(quarter)) % 4
        co, si = ((1, 0), (0, 1), (-1, 0), (0, -1))[q]
        block = out[r0:r1, c0:c1]
        for oy in offs:
            for ox in offs:
                dx = gx0 + ox - pl.cx
                dy = gy0 + oy - pl.cy
                if co:      # u from x, v from y
                    pc = _index(co * dx, pl.size_x, pw, w)
                    pr = _index_v(co * dy, pl.size_y, ph, h)
                    block |= padded[np.ix_(pr, pc)]
                else:       # u from y, v from x
                    pc = _index(si * dy, pl.size_x, pw, w)
                    pr = _index_v(-si * dx, pl.size_y, ph, h)
                    block |= padded[np.ix_(pr, pc)].T
                if boundary:
                    ub = (si * dy if not co else co * dx)
                    vb = (-si * dx if not co else co * dy)
                    if co:
                        block |= _edge(vb, pl.size_y, res)[:, None] & _inside(ub, pl.size_x)
                        block |= _edge(ub, pl.size_x, res)[None, :] & _inside(vb, pl.size_y)[
                            :, None]
                    else:
                        block |= _edge(ub, pl.size_x, res)[:, None] & _inside(vb, pl.size_y)
                        block |= _edge(vb, pl.size_y, res)[None, :] & _inside(ub, pl.size_x)[
                            :, None]
        return out
    c, s = math.cos(pl.yaw), math.sin(pl.yaw)
    for a in range(r0, r1, ROW_CHUNK):
        b = min(r1, a + ROW_CHUNK)
        block = out[a:b, c0:c1]
        for oy in offs:
            for ox in offs:
                dx = (gx0 + ox - pl.cx)[None, :]
                dy = (grid.origin_y + np.arange(a, b) * res + oy - pl.cy)[:, None]
                u = c * dx + s * dy
                v = -s * dx + c * dy
                pc = _index(u, pl.size_x, pw, w)
                pr = _index_v(v, pl.size_y, ph, h)
                block |= padded[pr, pc]
                if boundary:
                    block |= ((_edge(u, pl.size_x, res) & _inside(v, pl.size_y))
                              | (_edge(v, pl.size_y, res) & _inside(u, pl.size_x)))
    return out


def _index(u, size, pw, w):
    """Pixel column of local coordinate u (box centred on 0), -1 outside the box."""
    i = np.floor((u + size / 2) / pw).astype(np.int64)
    i[(i < 0) | (i >= w)] = -1
    return i


def _index_v(v, size, ph, h):
    """Pixel row of local coordinate v (up), row 0 at the top; -1 outside the box."""
    i = np.floor((size / 2 - v) / ph).astype(np.int64)
    i[(i < 0) | (i >= h)] = -1
    return i


def _inside(u, size):
    return (u >= -size / 2) & (u <= size / 2)


def _edge(u, size, res):
    """Within one cell inside either edge of the box: the `boundary` wall."""
    return ((u >= -size / 2) & (u < -size / 2 + res)) | ((u <= size / 2) & (u > size / 2 - res))
