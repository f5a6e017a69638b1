"""Unit tests of turtle_lite.canvas: non-antialiased pen lines and colour sampling."""

import numpy as np
import pytest
from course_common.arena import METER_PX, SPAWN_M
from turtle_lite.canvas import Canvas, qt_round
from turtle_lite.world import DEFAULT_PEN_RGB, World

BG = (69, 86, 255)
PEN = (179, 184, 255)


def pen_mask(canvas, rgb=PEN):
    return (canvas.pixels == np.asarray(rgb, dtype=np.uint8)).all(axis=2)


def test_fill_and_version():
    canvas = Canvas(BG)
    assert canvas.pixels.shape == (500, 500, 3)
    assert canvas.pixels.dtype == np.uint8
    assert (canvas.pixels == BG).all()
    version = canvas.version
    canvas.fill((1, 2, 3))
    assert (canvas.pixels == (1, 2, 3)).all()
    assert canvas.version > version


@pytest.mark.parametrize('value, expected', [(249.5, 250), (249.49, 249), (0.0, 0), (499.0, 499),
                                             (10.5000001, 11)])
def test_qt_round(value, expected):
    assert int(qt_round(value)) == expected


@pytest.mark.parametrize('width, rows', [(3, [48, 49, 50]), (1, [49]), (0, [49]),
                                         (4, [48, 49, 50, 51])])
def test_horizontal_line_covers_width_rows_without_antialiasing(width, rows):
    canvas = Canvas(BG)
    canvas.draw_line(100.0, 49.6, 120.0, 49.6, PEN, width)
    mask = pen_mask(canvas)
    assert sorted(set(np.nonzero(mask)[0])) == rows
    # Only pen or background colours: no blending.
    other = ~(mask | pen_mask(canvas, BG))
    assert not other.any()


def test_square_caps_extend_half_width():
    canvas = Canvas(BG)
    canvas.draw_line(100.0, 50.5, 110.0, 50.5, PEN, 3)
    cols = np.nonzero(pen_mask(canvas)[50])[0]
    # centres from 98.5 to 111.5 are covered: columns 98..111
    assert cols.min() == 98 and cols.max() == 111


def test_diagonal_and_long_lines_and_order():
    canvas = Canvas(BG)
    canvas.draw_lines([0.0, 10.0], [0.0, 250.0], [499.0, 490.0], [499.0, 250.0],
                      np.array([PEN, (255, 0, 0)], dtype=np.uint8), [3, 1])
    mask = pen_mask(canvas)
    assert mask[250, 250] or mask[249, 250] or mask[250, 249]
    assert mask[0, 0] and mask[499, 499]
    assert pen_mask(canvas, (255, 0, 0))[249, 300]  # the later line is on top


def test_lines_outside_are_clipped():
    canvas = Canvas(BG)
    canvas.draw_line(-50.0, -50.0, 600.0, -50.0, PEN, 3)
    canvas.draw_line(-2.0, 0.5, 3.0, 0.5, PEN, 3)
    assert pen_mask(canvas)[0, :3].all()


def test_wide_pen_batch_and_single_paths_agree():
    a = Canvas(BG)
    b = Canvas(BG)
    a.draw_line(200.3, 200.7, 202.1, 203.9, PEN, 5)  # vectorised batch
    b._draw_single(200.3, 200.7, 202.1, 203.9, np.asarray(PEN, np.uint8), 2.5)  # one by one
    assert (a.pixels == b.pixels).all()


def test_sample_rounds_and_clips():
    canvas = Canvas(BG)
    canvas.pixels[10, 20] = (1, 2, 3)
    assert tuple(canvas.sample([19.6], [9.5])[0]) == (1, 2, 3)
    assert tuple(canvas.sample([1e9], [-5.0])[0]) == BG


@pytest.mark.parametrize('speed, low, high', [(1.0, 17, 22), (1.5, 8, 13), (2.0, 0, 3),
                                              (2.5, 0, 0), (3.0, 0, 0)])
def test_colour_sensor_while_moving_matches_turtlesim_table(speed, low, high):
    """The real node's figure: 25 samples heading +x with pen width 3 read the pen colour 19, 10,
    1 and 0 times at 1, 1.5, 2 and >= 2.5 m/s."""
    world = World()
    world.add_turtle('turtle1', 1.0, SPAWN_M, 0.0)
    world.set_command('turtle1', speed, 0.0, 0.0, now=0.0)
    world.step(0.0)
    world.step(0.0)
    pen_hits = 0
    samples = 100
    for _ in range(samples):
        result = world.step(0.0)
        pen_hits += tuple(result.colors[0]) == DEFAULT_PEN_RGB
    assert low <= pen_hits * 25 / samples <= high
    assert METER_PX == 45.0
