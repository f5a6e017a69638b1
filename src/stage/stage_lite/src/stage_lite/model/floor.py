"""The static bodies as a filled raster, for pictures, /map and placing robots (no rospy).

Stage's grid holds only the outlines of bodies (grid.py); a picture or a map wants them
filled: a floor plan's occupied pixels, a box's whole footprint. filled() gives that, on the
world's cells, together with the outline cells Stage itself uses; coarsen() shrinks it for a
coarser map or a zoomed-out picture without losing a thin wall.
"""
import math

import numpy as np

ROW_CHUNK = 512       # cell rows sampled at once (bounds the temporary arrays)


def filled(models, outline_xy, robot_xy, ppm):
    """(occupied bool [rows, cols], origin_x, origin_y, resolution): row 0 is the lowest y.

    models: the static models; outline_xy: (x, y) int arrays of their outline cells;
    robot_xy: the robots' start positions (m), kept inside the raster."""
    xs, ys = outline_xy
    cx = [int(xs.min()), int(xs.max())] if xs.size else []
    cy = [int(ys.min()), int(ys.max())] if ys.size else []
    for x, y in robot_xy:
        cx.append(math.floor(x * ppm))
        cy.append(math.floor(y * ppm))
    if not cx:
        return np.zeros((1, 1), bool), 0.0, 0.0, 1.0 / ppm
    x0, x1, y0, y1 = min(cx) - 2, max(cx) + 2, min(cy) - 2, max(cy) + 2
    occ = np.zeros((y1 - y0 + 1, x1 - x0 + 1), bool)
    occ[ys - y0, xs - x0] = True
    for m in models:
        if m.bitmap is not None:
            _fill_bitmap(occ, m, x0, y0, ppm)
        else:
            for block in m.blocks:
                _fill_polygon(occ, m.pixel_vertices(block, ppm), x0, y0)
    return occ, x0 / ppm, y0 / ppm, 1.0 / ppm


def _fill_bitmap(occ, m, x0, y0, ppm):
    """Cells whose centre lies in an occupied pixel of the model's image."""
    img, minx, maxx, miny, maxy = m.bitmap
    bx, by, _, ba = m.body_pose()
    half = math.hypot(m.geom_size[0], m.geom_size[1]) / 2.0
    c0 = max(0, math.floor((bx - half) * ppm) - x0)
    c1 = min(occ.shape[1], math.ceil((bx + half) * ppm) - x0 + 1)
    r0 = max(0, math.floor((by - half) * ppm) - y0)
    r1 = min(occ.shape[0], math.ceil((by + half) * ppm) - y0 + 1)
    if c0 >= c1 or r0 >= r1:
        return
    sx, sy = maxx - minx, maxy - miny
    kx = sx / m.geom_size[0] if m.geom_size[0] else 0.0
    ky = sy / m.geom_size[1] if m.geom_size[1] else 0.0
    cos, sin = math.cos(ba), math.sin(ba)
    cell_x = (x0 + np.arange(c0, c1) + 0.5) / ppm - bx
    h, w = img.shape
    for a in range(r0, r1, ROW_CHUNK):
        b = min(r1, a + ROW_CHUNK)
        cell_y = ((y0 + np.arange(a, b) + 0.5) / ppm - by)[:, None]
        xl = cell_x[None, :] * cos + cell_y * sin
        yl = -cell_x[None, :] * sin + cell_y * cos
        col = np.floor(xl * kx + (minx + sx / 2.0)).astype(np.int64)
        row = np.floor(-(yl * ky + (miny + sy / 2.0))).astype(np.int64)
        inside = (col >= 0) & (col < w) & (row >= 0) & (row < h)
        hit = np.zeros(inside.shape, bool)
        hit[inside] = img[row[inside], col[inside]]
        occ[a:b, c0:c1] |= hit


def _fill_polygon(occ, vertices, x0, y0):
    """Cells whose centre lies inside the polygon (even-odd rule)."""
    vx = vertices[0] - x0
    vy = vertices[1] - y0
    c0, c1 = max(0, int(vx.min())), min(occ.shape[1], int(vx.max()) + 1)
    r0, r1 = max(0, int(vy.min())), min(occ.shape[0], int(vy.max()) + 1)
    if c0 >= c1 or r0 >= r1:
        return
    px = np.arange(c0, c1) + 0.5
    py = (np.arange(r0, r1) + 0.5)[:, None]
    inside = np.zeros((r1 - r0, c1 - c0), bool)
    n = len(vx)
    for i in range(n):
        xa, ya, xb, yb = vx[i], vy[i], vx[(i + 1) % n], vy[(i + 1) % n]
        if ya == yb:
            continue
        crosses = (py >= min(ya, yb)) & (py < max(ya, yb))
        xc = xa + (py - ya) * (xb - xa) / (yb - ya)
        inside ^= crosses & (px[None, :] < xc)
    occ[r0:r1, c0:c1] |= inside


def coarsen(grid, factor):
    """grid (bool, rows x cols) shrunk by an integer factor: a cell is True if any under it is."""
    if factor < 1 or int(factor) != factor:
        raise ValueError('the shrink factor must be a whole number >= 1, not %r' % (factor,))
    factor = int(factor)
    rows, cols = grid.shape
    out_r, out_c = -(-rows // factor), -(-cols // factor)
    padded = np.zeros((out_r * factor, out_c * factor), dtype=bool)
    padded[:rows, :cols] = grid
    return padded.reshape(out_r, factor, out_c, factor).any(axis=(1, 3))
