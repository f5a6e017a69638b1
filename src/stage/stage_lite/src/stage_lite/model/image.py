"""Floor-plan images as Stage 4.3 reads them: pixels, then the outlines of the occupied ones.

Stage loads a `bitmap` with FLTK (Fl_Shared_Image) and looks at each pixel's FIRST channel
only: a pixel is free when that channel is > 127 (libstage/stage.cc; alpha is ignored, a
red pixel is free, a blue one occupied). FLTK's own readers give that channel as follows, and
so does first_channel():
- PGM/PPM (P2, P3, P5, P6): binary files with maxval < 256 are taken raw, NOT rescaled (a
  P5 with maxval 15 is all dark); maxval >= 256 and ASCII files are scaled by 255 * v / maxval
  in integers; PBM (P1, P4) bits set read 255: free (FLTK's quirk: PBM's black is free);
- PNG: palette colours expanded, 16-bit samples cut to their high byte, grey or red first;
- BMP, JPEG: red (or grey) first.

polygons() then traces Stage's outlines: every edge between an occupied pixel and a free one
(or the image border), directed, chained into polygons exactly as polys_from_image_file
chains them (its std::set and std::multimap orders, its merging of straight runs), with the
image's y axis flipped. Only these outlines become obstacles in Stage's grid.
"""
import io

import numpy as np

from .jit import kernel, njit
from .worldfile import WorldError

#: Stage: a pixel whose first channel is above this is free floor.
FREE_ABOVE = 127


def first_channel(path):
    """(H, W) uint8: each pixel's first channel as FLTK gives it, row 0 at the top.
    WorldError if the file is missing or no image Stage reads."""
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except FileNotFoundError:
        raise WorldError(path, None, 'bitmap file does not exist') from None
    except OSError as e:
        raise WorldError(path, None, 'cannot read bitmap: %s' % e.strerror) from None
    if data[:1] == b'P' and data[1:2] in b'123456' and len(data) > 2:
        return _pnm(data, path)
    try:
        from PIL import Image
        with Image.open(io.BytesIO(data)) as im:
            im.load()
            return _pil_first_channel(im)
    except ImportError:
        raise WorldError(path, None, 'PNG, BMP and JPEG bitmaps need python3-pil') from None
    except Exception:
        raise WorldError(path, None, 'not an image Stage reads (PGM, PNG, BMP or JPEG)'
                         ) from None


def _pil_first_channel(im):
    mode = im.mode
    if mode in ('I;16', 'I;16B', 'I;16L', 'I'):
        a = np.asarray(im, dtype=np.int64)
        return (a >> 8).clip(0, 255).astype(np.uint8)   # libpng's strip_16: the high byte
    if mode in ('L', 'LA'):
        return np.asarray(im.getchannel(0), dtype=np.uint8)
    if mode == '1':
        return np.asarray(im.convert('L'), dtype=np.uint8)
    if mode not in ('RGB', 'RGBA'):
        im = im.convert('RGBA' if 'transparency' in im.info or mode == 'PA' else 'RGB')
    return np.asarray(im.getchannel(0), dtype=np.uint8)


def _pnm_header(data):
    """(format, width, height, maxval, offset of the pixels), FLTK's header reading: numbers
    anywhere on the lines after 'P<n>', '#' ends a line, the pixels start on the line after
    the one holding the last header number."""
    lines = data.split(b'\n')
    fmt = int(data[1:2])
    need = 2 if fmt in (1, 4) else 3
    nums = []
    pos = 0
    first = True
    for line in lines:
        end = pos + len(line) + 1
        text = line[2:] if first else line
        first = False
        k = 0
        while k < len(text) and len(nums) < need:
            c = text[k:k + 1]
            if c == b'#':
                break
            if c.isdigit():
                j = k
                while j < len(text) and text[j:j + 1].isdigit():
                    j += 1
                nums.append(int(text[k:j]))
                k = j
            else:
                k += 1
        pos = end
        if len(nums) == need:
            break
    if len(nums) < need:
        return None
    w, h = nums[0], nums[1]
    maxval = nums[2] if need == 3 else 1
    return fmt, w, h, maxval, pos


def _pnm(data, path):
    head = _pnm_header(data)
    if head is None or head[1] <= 0 or head[2] <= 0 or head[3] <= 0:
        raise WorldError(path, None, 'not a valid PNM image (bad header)')
    fmt, w, h, maxval, pos = head
    depth = 3 if fmt in (3, 6) else 1
    count = w * h * depth
    if fmt in (5, 6):
        if maxval < 256:
            raw = np.frombuffer(data, np.uint8, min(count, len(data) - pos), pos)
            vals = raw.astype(np.int64)
        else:
            raw = np.frombuffer(data, '>u2', min(count, (len(data) - pos) // 2), pos)
            vals = raw.astype(np.int64) * 255 // maxval
    elif fmt == 4:
        bits = np.unpackbits(np.frombuffer(data, np.uint8, offset=pos))
        stride = (w + 7) // 8 * 8
        rows = bits[:stride * h].reshape(-1, stride)[:, :w] if bits.size >= stride else bits[:0]
        vals = rows.astype(np.int64).ravel() * 255
    else:
        try:
            text = data[pos:].split()
            vals = np.array([int(t) for t in text[:count]], dtype=np.int64) * 255 // maxval
        except ValueError:
            raise WorldError(path, None, 'not a valid PNM image (bad pixel value)') from None
    if vals.size < count:
        raise WorldError(path, None, 'not a valid PNM image (truncated pixel data)')
    return vals.reshape(h, w, depth)[:, :, 0].astype(np.uint8)


def occupied(first):
    """Bool (H, W): Stage's obstacle pixels (first channel <= 127)."""
    return first <= FREE_ABOVE


def boundary_edges(occ):
    """Every directed edge between an occupied pixel and a free one or the border, as rows
    (x1, y1, x2, y2) in pixel corners (y down), sorted as Stage's std::set of edges."""
    h, w = occ.shape
    pad = np.zeros((h + 2, w + 2), bool)
    pad[1:-1, 1:-1] = occ
    inner = pad[1:-1, 1:-1]
    ys, xs = np.nonzero(inner & ~pad[:-2, 1:-1])          # top: (x,y) -> (x+1,y)
    top = np.column_stack((xs, ys, xs + 1, ys))
    ys, xs = np.nonzero(inner & ~pad[1:-1, 2:])           # right: (x+1,y) -> (x+1,y+1)
    right = np.column_stack((xs + 1, ys, xs + 1, ys + 1))
    ys, xs = np.nonzero(inner & ~pad[2:, 1:-1])           # bottom: (x+1,y+1) -> (x,y+1)
    bottom = np.column_stack((xs + 1, ys + 1, xs, ys + 1))
    ys, xs = np.nonzero(inner & ~pad[1:-1, :-2])          # left: (x,y+1) -> (x,y)
    left = np.column_stack((xs, ys + 1, xs, ys))
    edges = np.vstack((top, right, bottom, left)).astype(np.int64)
    order = np.lexsort((edges[:, 3], edges[:, 2], edges[:, 1], edges[:, 0]))
    return edges[order]


@kernel
def _direction(a):
    return 0.0 if a == 0.0 else (-1.0 if a < 0.0 else 1.0)


@njit(cache=True)
def _trace(edges, height):
    """Stage's chaining of sorted edges into polygons: (points (N, 2) float64 with y flipped,
    offsets (P + 1) of each polygon's first point)."""
    n = edges.shape[0]
    stride = height + 1
    nverts = (edges[:, 0].max() + 2) * stride if n else 1
    first = np.full(nverts, -1, np.int64)
    for k in range(n - 1, -1, -1):
        first[edges[k, 0] * stride + edges[k, 1]] = k
    used = np.zeros(n, np.bool_)
    pts = np.empty((n, 2), np.float64)
    offsets = [0]
    npts = 0
    begin = 0
    while True:
        while begin < n and used[begin]:
            begin += 1
        if begin >= n:
            break
        start = npts
        seed = begin
        while seed >= 0:
            px = float(edges[seed, 0])
            py = -float(edges[seed, 1])
            size = npts - start
            merged = False
            if size > 2:
                ldx = _direction(pts[npts - 1, 0] - pts[npts - 2, 0])
                ldy = _direction(pts[npts - 1, 1] - pts[npts - 2, 1])
                ndx = _direction(px - pts[npts - 1, 0])
                ndy = _direction(py - pts[npts - 1, 1])
                if ldx == ndx and ldy == ndy:
                    pts[npts - 1, 0] = px
                    pts[npts - 1, 1] = py
                    merged = True
            if not merged:
                pts[npts, 0] = px
                pts[npts, 1] = py
                npts += 1
            used[seed] = True
            nx = edges[seed, 2]
            ny = edges[seed, 3]
            seed = -1
            if nx * stride + ny < nverts:
                k = first[nx * stride + ny]
                while k >= 0 and k < n and edges[k, 0] == nx and edges[k, 1] == ny:
                    if not used[k]:
                        seed = k
                        break
                    k += 1
        offsets.append(npts)
    return pts[:npts].copy(), np.array(offsets, np.int64)


def polygons(occ):
    """Stage's polygons of an occupancy image: a list of (N, 2) float64 arrays of pixel
    corners (x right, y up: the image's rows negated), in Stage's order."""
    edges = boundary_edges(occ)
    if edges.shape[0] == 0:
        return []
    pts, offsets = _trace(edges, occ.shape[0])
    return [pts[offsets[k]:offsets[k + 1]] for k in range(len(offsets) - 1)]
