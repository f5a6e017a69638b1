"""The 500x500 drawing canvas: background, pen trails, colour sampling (pure numpy, no rospy).

Mirrors turtlesim's ``path_image_`` (a QImage filled with the background, trails drawn
with a non-antialiased QPainter) closely enough that ``color_sensor`` behaves the same:

* Pixel (col, row) has its centre at (col + 0.5, row + 0.5) in canvas pixels.
* A line of width ``w`` from A to B covers every pixel whose centre lies in the rectangle
  A..B widened by w/2 on both sides and extended by w/2 beyond both ends (Qt's default
  square cap). Across the line the band is half-open, so exactly ``w`` rows are covered
  by an axis-aligned line. With this rule the fraction of colour samples that read the pen
  colour under a turtle moving along +x at 1, 1.5, 2 and 2.5 m/s is 0.78, 0.42, 0.06 and 0,
  which is what the real node measured (19/25, 10/25, 1/25, 0/25 colour samples).
* Sampling uses Qt's ``QPointF::toPoint()`` rounding: floor(v + 0.5).

Canvas coordinates are screen pixels: column = 45 * x, row = 45 * y_s (y_s points down).
"""

import numpy as np

WIDTH_PX = 500
HEIGHT_PX = 500
#: Segments whose bounding box fits in this many pixels per side are rasterised together in
#: one vectorised batch; longer ones (teleports, very fast turtles, wide pens) one by one.
_BATCH_BOX_PX = 12
_OFFSETS = np.arange(_BATCH_BOX_PX, dtype=np.float64)


def qt_round(values):
    """Round like Qt's qRound for the non-negative coordinates used here: floor(v + 0.5)."""
    return np.floor(np.asarray(values, dtype=np.float64) + 0.5).astype(np.int64)


class Canvas:
    """An RGB uint8 image of HEIGHT_PX rows and WIDTH_PX columns with pen-line drawing."""

    def __init__(self, background=(69, 86, 255), width=WIDTH_PX, height=HEIGHT_PX):
        self.width = int(width)
        self.height = int(height)
        self.pixels = np.empty((self.height, self.width, 3), dtype=np.uint8)
        #: Incremented on every change, so a viewer can skip redrawing an unchanged canvas.
        self.version = 0
        self.fill(background)

    def fill(self, rgb):
        """Fill the whole canvas with ``rgb`` (erases every trail)."""
        self.pixels[:, :] = np.asarray(rgb, dtype=np.uint8)
        self.version += 1

    def sample(self, cols, rows):
        """Colours (N x 3 uint8) at float pixel positions, rounded like Qt; clipped to the image."""
        # np.minimum/np.maximum: np.clip has a much larger fixed cost on small arrays.
        c = np.minimum(np.maximum(qt_round(cols), 0), self.width - 1)
        r = np.minimum(np.maximum(qt_round(rows), 0), self.height - 1)
        return self.pixels[r, c]

    def draw_line(self, x0, y0, x1, y1, rgb, width):
        """Draw one line in pixel coordinates (see the module docstring for the pixel rule)."""
        self.draw_lines(np.array([x0], dtype=np.float64), np.array([y0], dtype=np.float64),
                        np.array([x1], dtype=np.float64), np.array([y1], dtype=np.float64),
                        np.asarray([rgb], dtype=np.uint8), np.array([width]))

    def draw_lines(self, x0, y0, x1, y1, rgb, width):
        """Draw N lines in order (later lines on top). Arrays of length N; rgb is N x 3.

        A width of 0 draws 1 px wide (Qt's cosmetic pen), as turtlesim's set_pen does.
        """
        x0 = np.asarray(x0, dtype=np.float64)
        if x0.size == 0:
            return
        y0 = np.asarray(y0, dtype=np.float64)
        x1 = np.asarray(x1, dtype=np.float64)
        y1 = np.asarray(y1, dtype=np.float64)
        rgb = np.asarray(rgb, dtype=np.uint8).reshape(-1, 3)
        half = np.maximum(np.asarray(width, dtype=np.float64), 1.0) / 2.0
        # Bounding box of the capped rectangle.
        left = np.floor(np.minimum(x0, x1) - half)
        top = np.floor(np.minimum(y0, y1) - half)
        span = np.maximum(np.abs(x1 - x0), np.abs(y1 - y0)) + 2.0 * half + 2.0
        small = span <= _BATCH_BOX_PX
        # The batch works on N x box x box pixels: keep the box as small as this batch needs.
        box = int(np.ceil(span[small].max())) if small.any() else 0
        if small.all():
            self._draw_batch(x0, y0, x1, y1, rgb, half, left, top, box)
        else:
            # Keep drawing order: batch runs of small segments, long ones one at a time.
            n = x0.size
            i = 0
            while i < n:
                j = i
                while j < n and small[j] == small[i]:
                    j += 1
                sl = slice(i, j)
                if small[i]:
                    self._draw_batch(x0[sl], y0[sl], x1[sl], y1[sl], rgb[sl], half[sl],
                                     left[sl], top[sl], box)
                else:
                    for k in range(i, j):
                        self._draw_single(x0[k], y0[k], x1[k], y1[k], rgb[k], half[k])
                i = j
        self.version += 1

    @staticmethod
    def _frame(x0, y0, x1, y1):
        """Unit direction (ux, uy) and length of each segment; +x for zero-length ones."""
        dx = x1 - x0
        dy = y1 - y0
        length = np.hypot(dx, dy)
        safe = np.where(length > 0.0, length, 1.0)
        ux = np.where(length > 0.0, dx / safe, 1.0)
        uy = np.where(length > 0.0, dy / safe, 0.0)
        return ux, uy, length

    def _mask(self, cx, cy, x0, y0, ux, uy, length, half):
        """True where the pixel centre (cx, cy) lies inside the capped, widened segment."""
        px = cx - x0
        py = cy - y0
        along = px * ux + py * uy
        across = py * ux - px * uy
        return ((along >= -half) & (along <= length + half)
                & (across >= -half) & (across < half))

    def _draw_batch(self, x0, y0, x1, y1, rgb, half, left, top, box):
        ux, uy, length = self._frame(x0, y0, x1, y1)
        offsets = _OFFSETS[:box]
        col = left[:, None, None] + offsets[None, None, :]           # N x 1 x K
        row = top[:, None, None] + offsets[None, :, None]            # N x K x 1
        e = (slice(None), None, None)
        inside = self._mask(col + 0.5, row + 0.5, x0[e], y0[e], ux[e], uy[e], length[e],
                            half[e])
        inside &= (col >= 0) & (col < self.width) & (row >= 0) & (row < self.height)
        seg, rr, cc = np.nonzero(inside)
        if seg.size:
            self.pixels[(top[seg] + rr).astype(np.int64),
                        (left[seg] + cc).astype(np.int64)] = rgb[seg]

    def _draw_single(self, x0, y0, x1, y1, rgb, half):
        ux, uy, length = (float(v) for v in self._frame(np.float64(x0), np.float64(y0),
                                                         np.float64(x1), np.float64(y1)))
        c_lo = max(int(np.floor(min(x0, x1) - half)), 0)
        c_hi = min(int(np.ceil(max(x0, x1) + half)) + 1, self.width)
        r_lo = max(int(np.floor(min(y0, y1) - half)), 0)
        r_hi = min(int(np.ceil(max(y0, y1) + half)) + 1, self.height)
        if c_lo >= c_hi or r_lo >= r_hi:
            return
        cols = np.arange(c_lo, c_hi, dtype=np.float64)[None, :] + 0.5
        rows = np.arange(r_lo, r_hi, dtype=np.float64)[:, None] + 0.5
        inside = self._mask(cols, rows, x0, y0, ux, uy, length, half)
        self.pixels[r_lo:r_hi, c_lo:c_hi][inside] = rgb
