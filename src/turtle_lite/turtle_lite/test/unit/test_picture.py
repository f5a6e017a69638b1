"""Unit tests of turtle_lite.picture: rendering turtles and writing PNGs."""

import numpy as np
from course_common.arena import SPAWN_M
from PIL import Image
from turtle_lite.canvas import Canvas
from turtle_lite.picture import SHELL_RGB, render, save_png

BG = (69, 86, 255)


def test_render_draws_sprite_at_pose_without_touching_canvas():
    canvas = Canvas(BG)
    image = render(canvas.pixels, [(SPAWN_M, SPAWN_M, 0.0)])
    assert image.size == (500, 500)
    assert image.getpixel((250, 250)) == SHELL_RGB
    assert image.getpixel((5, 5)) == BG
    assert (canvas.pixels == BG).all()


def test_sprite_is_rotated_by_theta():
    canvas = Canvas(BG)
    east = np.asarray(render(canvas.pixels, [(SPAWN_M, SPAWN_M, 0.0)]))
    north = np.asarray(render(canvas.pixels, [(SPAWN_M, SPAWN_M, np.pi / 2)]))
    # The head is ahead of the shell: right of centre facing east, above it facing north.
    assert tuple(east[249, 265]) != BG and tuple(east[234, 249]) == BG
    assert tuple(north[234, 249]) != BG and tuple(north[249, 265]) == BG


def test_save_png_creates_directories_and_returns_absolute_path(tmp_path):
    canvas = Canvas(BG)
    canvas.draw_line(10.0, 10.0, 100.0, 10.0, (179, 184, 255), 3)
    path = save_png(str(tmp_path / 'a' / 'b' / 'pic.png'), canvas.pixels, [])
    assert path == str(tmp_path / 'a' / 'b' / 'pic.png')
    with Image.open(path) as image:
        assert image.format == 'PNG'
        assert image.getpixel((50, 10)) == (179, 184, 255)
        assert image.getpixel((300, 300)) == BG
