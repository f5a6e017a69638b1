#!/usr/bin/python3
"""Draws the workspace's own office floor plan, world/office.pgm (binary P5, no randomness).

Run: `/usr/bin/python3 draw_office.py [OUT]` (default: office.pgm beside this script).

The lesson world places it with `size [54.0 58.7 0.5] pose [-29.35 27.0 0 90.0]`: image
columns run along world +y, image rows (top to bottom) along world +x, and the outer wall fills
the image border, so the occupied bounding box is the whole 540 x 587 image and one pixel is
0.1 m x 0.1 m exactly. The plan covers x in [-58.7, 0], y in [0, 54]. Everything below is drawn
in those world metres.

The lesson's geometry it must give: the robots start in an open hall at (-11.5, 23.5),
(-13.5, 23.5), (-11.5, 21.5), (-13.5, 21.5) facing +x, and the hall's east wall (a solid run
of it, no door) has its face at x = -9.6, 1.775 m ahead of the front robots' noses.
"""

import os
import sys

import numpy as np

PX = 0.1                       # m per pixel
WIDTH, HEIGHT = 540, 587       # columns (world y, 54 m) x rows (world x, 58.7 m)
X0 = -58.7                     # world x of the top image row's top edge
WALL = 0.2                     # m, interior wall thickness
DOOR = 1.0                     # m, door width
FREE, OCCUPIED = 254, 0

# (x, y) of the hall's east wall face, the wall the lesson's front pair runs into
EAST_HALL_FACE_X = -9.6


class Plan:
    """A pixel canvas addressed in world metres."""

    def __init__(self):
        self.img = np.full((HEIGHT, WIDTH), FREE, np.uint8)
        xs = X0 + (np.arange(HEIGHT) + 0.5) * PX
        ys = (np.arange(WIDTH) + 0.5) * PX
        self.x = xs[:, None]
        self.y = ys[None, :]

    def box(self, x0, x1, y0, y1, value=OCCUPIED):
        """Fills the pixels whose centres lie in [x0, x1] x [y0, y1]."""
        m = (self.x >= x0) & (self.x <= x1) & (self.y >= y0) & (self.y <= y1)
        self.img[m] = value

    def wall_x(self, x, y0, y1, doors=()):
        """A wall of constant x (its west face at x) from y0 to y1, door gaps centred on
        each y of `doors`."""
        self.box(x, x + WALL - 1e-6, y0, y1)
        for d in doors:
            self.box(x, x + WALL - 1e-6, d - DOOR / 2, d + DOOR / 2, FREE)

    def wall_y(self, y, x0, x1, doors=()):
        """A wall of constant y (its south face at y) from x0 to x1, doors centred on x."""
        self.box(x0, x1, y, y + WALL - 1e-6)
        for d in doors:
            self.box(d - DOOR / 2, d + DOOR / 2, y, y + WALL - 1e-6, FREE)


def draw():
    p = Plan()
    # outer wall: two pixels round the border, so the occupied bbox is the whole image
    p.img[:2, :] = p.img[-2:, :] = OCCUPIED
    p.img[:, :2] = p.img[:, -2:] = OCCUPIED

    # east offices: x in [-9.4, 0], one room per 6 m of y, a door each onto the hall; no door
    # in y [20, 25], where the lesson's robots meet the wall
    p.wall_x(EAST_HALL_FACE_X, 0, 54, doors=(3.5, 9.5, 15.5, 19.2, 28.5, 33.5, 39.5, 45.5,
                                             51.5))
    for k in range(1, 9):
        p.wall_y(6.0 * k, -9.4, 0)
    # the hall, x in [-20, -9.6]: closed to the north at y = 40 (door away from the lanes) and
    # to the south at y = 10, two pillars
    p.wall_y(40.0, -20.0, -9.6, doors=(-17.5,))
    p.wall_y(10.0, -20.0, -9.6, doors=(-15.0,))
    p.box(-16.4, -15.6, 31.6, 32.4)
    p.box(-16.4, -15.6, 15.6, 16.4)
    # middle block: two rows of rooms either side of x = -28, cut by a cross corridor at
    # y in [26, 28.5] that joins the hall to the west corridor
    p.wall_x(-20.2, 0, 54, doors=(3.0, 9.0, 15.0, 21.0, 27.25, 33.0, 45.0, 51.0))
    p.wall_x(-28.2, 0, 26.0, doors=(3.0, 9.0, 15.0, 21.0))
    p.wall_x(-28.2, 28.5, 54, doors=(37.5, 43.5, 50.0))
    p.wall_x(-36.2, 0, 54, doors=(3.0, 9.0, 15.0, 21.0, 27.25, 33.0, 39.0, 45.0, 51.0))
    p.wall_y(25.8, -36.0, -20.2)
    p.wall_y(28.5, -36.0, -20.2)
    for y in (6.0, 12.0, 18.0, 34.5, 40.5, 46.5):
        p.wall_y(y, -36.0, -20.2)
    # west corridor x in [-38.5, -36.2]; west wing: labs and a conference room
    p.wall_x(-38.7, 0, 54, doors=(4.0, 14.0, 24.0, 30.0, 44.0, 50.0))
    p.wall_y(20.0, -58.7, -38.7, doors=(-43.0, -54.0))
    p.wall_y(36.0, -58.7, -38.7, doors=(-44.0, -53.0))
    p.wall_x(-48.8, 0, 20.0, doors=(10.0,))
    p.wall_x(-48.8, 36.2, 54, doors=(45.0,))
    # furniture-like blocks in the conference room (x [-48.6, -38.9], y [20.2, 36])
    p.box(-46.0, -42.0, 26.0, 30.0)
    return p.img


def write_pgm(img, path):
    h, w = img.shape
    with open(path, 'wb') as f:
        f.write(b'P5\n%d %d\n255\n' % (w, h))
        f.write(img.tobytes())


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    out = argv[0] if argv else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                            'office.pgm')
    write_pgm(draw(), out)
    print('wrote %s' % out)


if __name__ == '__main__':
    main()
