"""A Stage 4.3 model's body: blocks, their bounding box and CalcSize (no rospy).

libstage/block.cc and blockgroup.cc, in Stage's order of operations (a body's cells come
from flooring coordinates that went through these sums): a block is a polygon in its model's
frame with a height range; CalcSize scales ALL the blocks of a body so that their bounding
box fills the model's size (x, y about the box's centre, z from 0); a `block( )`'s points are
made counter-clockwise.
"""
import math

import numpy as np

BILLION = 1e9                         # BlockGroup::BoundingBox's starting extremes
DBL_EPSILON = 2.220446049250313e-16


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


def rasterize(blocks, size, width, height, cell_w, cell_h):
    """Model::Rasterize (Block::Rasterize of each block): the outline of every block drawn
    into a width x height raster of cells cell_w x cell_h metres from the model's bottom left
    corner, an edge at a time from its first point, stepping along its longer axis; a
    bytearray, row y from the bottom, 1 where an outline passes. A cell outside the raster
    is skipped as Stage skips it: with `continue`, past the step of y along the edge, so
    an edge that starts outside stays on the row it started on (and outside)."""
    data = bytearray(width * height)
    for b in blocks:
        pts = b.pts.tolist()
        for i, (x1, y1) in enumerate(pts):
            x2, y2 = pts[(i + 1) % len(pts)]
            ax = math.floor((x1 + size[0] / 2.0) / cell_w)
            ay = math.floor((y1 + size[1] / 2.0) / cell_h)
            bx = math.floor((x2 + size[0] / 2.0) / cell_w)
            by = math.floor((y2 + size[1] / 2.0) / cell_h)
            steep = abs(by - ay) > abs(bx - ax)
            if steep:
                ax, ay, bx, by = ay, ax, by, bx
            if ax > bx:
                ax, bx, ay, by = bx, ax, by, ay
            # C's double division; a one-cell edge (0/0) draws its cell once
            dydx = (by - ay) / (bx - ax) if bx != ax else math.nan
            y = float(ay)
            across, along = (height, width) if steep else (width, height)
            for x in range(ax, bx + 1):
                fy = math.floor(y) if not math.isnan(y) else None
                if fy is None or not (0 <= x < across and 0 <= fy < along):
                    continue
                data[fy + x * width if steep else x + fy * width] = 1
                y += dydx
    return data
