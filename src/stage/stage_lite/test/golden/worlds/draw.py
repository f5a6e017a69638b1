#!/usr/bin/python3
"""Draws the floor plans of the golden worlds (no randomness): `draw.py [OUT_DIR]`.

plan.pgm (binary P5, 300 x 200 px), the floor of plan.world: an outer wall, rooms with
doors, thin walls one pixel wide, diagonal walls at several slopes, a solid block (Stage
draws only its outline), single pixels, a checkerboard patch (pixels touching at corners),
and a run of grey levels from 120 to 135 (Stage: <= 127 is an obstacle).

The images of formats.world, one per file format Stage reads, each 40 x 40 px with the same
pattern (a square ring with a gap, a diagonal, dots) coded in that format's own way:
PGM binary (maxval 255, and 15: FLTK takes binary values below 256 unscaled), PGM ASCII
(maxval 1000) and 16-bit binary, PBM (FLTK reads a set bit as white: free), PNG grey, RGB
(red pixels are free, blue ones obstacles: Stage reads the first channel), RGBA (alpha is
ignored), palette and 16-bit grey, BMP, and JPEG (lossy: its grey edges near 127 decide).
"""
import os
import sys

import numpy as np

FREE, WALL = 255, 0


def plan():
    img = np.full((200, 300), FREE, np.uint8)
    img[0, :] = img[-1, :] = WALL
    img[:, 0] = img[:, -1] = WALL
    img[100, 1:140] = WALL                 # a thin wall with a door
    img[100, 60:75] = FREE
    img[1:100, 140] = WALL                 # another, with a door
    img[40:52, 140] = FREE
    img[60:63, 180:290] = WALL             # a wall three pixels thick
    img[150:170, 200:230] = WALL           # a solid block
    for k, (dy, dx) in enumerate(((1, 3), (1, 2), (1, 1), (2, 1), (5, 2))):
        y, x = 120 + 12 * k, 20
        for t in range(40):                # diagonal walls, one pixel wide
            yy, xx = y + (t * dy) // max(dx, dy), x + 2 * t * dx // max(dx, dy) // 2
            if 0 < yy < 199 and 0 < xx < 299:
                img[yy, xx + 60] = WALL
    for k in range(16):                    # grey levels around Stage's threshold
        img[20:24, 30 + 3 * k] = 120 + k
    for y in range(170, 180):              # checkerboard: pixels touching at corners
        for x in range(100, 110):
            if (x + y) % 2 == 0:
                img[y, x] = WALL
    for x in range(250, 290, 7):           # single pixels
        img[130, x] = WALL
    return img


def pattern():
    """40 x 40 bool: the obstacles of the format images."""
    p = np.zeros((40, 40), bool)
    p[4, 4:36] = p[35, 4:36] = True
    p[4:36, 4] = p[4:36, 35] = True
    p[15:25, 35] = False                   # the gap
    for t in range(10, 30):
        p[t, t] = True                     # a diagonal
    p[8, 30] = p[30, 8] = p[20, 12] = True
    return p


def write_pgm(path, values, maxval, binary=True):
    h, w = values.shape
    with open(path, 'wb') as f:
        f.write(b'P%d\n# golden world image\n%d %d\n%d\n' % (5 if binary else 2, w, h, maxval))
        if binary:
            f.write(values.astype('>u2' if maxval > 255 else np.uint8).tobytes())
        else:
            for row in values:
                f.write((' '.join(str(int(v)) for v in row) + '\n').encode())


def write_pbm(path, occupied):
    h, w = occupied.shape
    bits = ~occupied                       # FLTK: a set bit reads white (free)
    with open(path, 'wb') as f:
        f.write(b'P4\n%d %d\n' % (w, h))
        f.write(np.packbits(bits, axis=1).tobytes())


def formats(out):
    from PIL import Image
    p = pattern()
    grey = np.where(p, 40, 230).astype(np.uint8)
    write_pgm(os.path.join(out, 'f_p5.pgm'), grey, 255)
    write_pgm(os.path.join(out, 'f_p5_15.pgm'), np.where(p, 2, 14), 15)
    write_pgm(os.path.join(out, 'f_p2.pgm'), np.where(p, 300, 900), 1000, binary=False)
    write_pgm(os.path.join(out, 'f_p5_16.pgm'), np.where(p, 1000, 60000), 65535)
    write_pbm(os.path.join(out, 'f_p4.pbm'), p)
    Image.fromarray(grey, 'L').save(os.path.join(out, 'f_grey.png'))
    rgb = np.zeros((40, 40, 3), np.uint8)
    rgb[~p] = (250, 250, 250)
    rgb[p] = (0, 0, 255)                   # blue: an obstacle (red channel 0)
    rgb[36:40, :] = (255, 0, 0)            # red: free (red channel 255), black to the eye
    Image.fromarray(rgb, 'RGB').save(os.path.join(out, 'f_rgb.png'))
    rgba = np.zeros((40, 40, 4), np.uint8)
    rgba[..., :3] = np.where(p, 0, 255)[..., None]
    rgba[..., 3] = 255
    rgba[0:3, :, 3] = 0                    # transparent black: still an obstacle
    rgba[0:3, :, :3] = 0
    Image.fromarray(rgba, 'RGBA').save(os.path.join(out, 'f_rgba.png'))
    Image.fromarray(grey, 'L').convert('P').save(os.path.join(out, 'f_pal.png'))
    Image.fromarray(np.where(p, 9000, 50000).astype(np.uint16)).save(
        os.path.join(out, 'f_16.png'))
    Image.fromarray(rgb, 'RGB').save(os.path.join(out, 'f.bmp'))
    Image.fromarray(np.where(p, 100, 160).astype(np.uint8), 'L').save(
        os.path.join(out, 'f.jpg'), quality=60)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    write_pgm(os.path.join(out, 'plan.pgm'), plan(), 255)
    formats(out)


if __name__ == '__main__':
    main()
