"""Unit tests of course_common.rviz.screen: is rviz's view showing the lesson, and its log."""

import numpy as np
import pytest
from course_common.rviz.colours import ARENA_RGB, PALETTE
from course_common.rviz.screen import (
    BACKGROUND,
    MIN_TEXT_PIXELS,
    colour_pixels,
    error_lines,
    missing_colours,
    render_area,
    shows_lesson,
)

WIDGET_GREY = (239, 239, 239)  # Qt's panels around the 3D view


def _rgb255(rgb):
    return tuple(round(255 * c) for c in rgb)


def screen(robots=0, text_px=0, arena=True, white_panel=True, text_grey=255):
    """A 400 x 600 screenshot: a white panel on the left, the 3D view (background) right."""
    img = np.zeros((400, 600, 3), dtype=np.uint8)
    img[:, :] = WIDGET_GREY
    if white_panel:
        img[50:350, 0:150] = (255, 255, 255)  # the Displays tree: white, outside the view
    img[20:380, 200:590] = BACKGROUND
    if arena:
        img[30, 210:580] = _rgb255(ARENA_RGB)   # one edge is enough: 370 px
    for i in range(robots):
        img[100 + 20 * i:105 + 20 * i, 300:310] = _rgb255(PALETTE[i])  # 50 px each
    if text_px:
        img[300, 220:220 + text_px] = (text_grey,) * 3
    return img


def test_render_area_cuts_the_widgets_off():
    view = render_area(screen())
    assert view.shape == (360, 390, 3)
    assert (view[5, 5] == BACKGROUND).all()


def test_render_area_found_by_a_map_that_covers_the_view():
    # Stage's view: the map's free cells (grey, a little noisy) fill the whole 3D view
    img = screen(arena=False)
    img[20:380, 200:590] = (190, 191, 193)
    assert render_area(img).size == 0  # no background left to find it by
    assert render_area(img, background_rgb=(192, 192, 192), tolerance=3).shape == (360, 390, 3)
    assert render_area(img, background_rgb=(192, 192, 192), tolerance=1).size == 0


def test_missing_colours_names_those_below_the_count():
    img = screen(robots=2)  # PALETTE[0], PALETTE[1]: 50 px each
    colours = {'first': PALETTE[0], 'second': PALETTE[1], 'third': PALETTE[2]}
    assert missing_colours(img, colours, 50) == ['third']
    assert missing_colours(img, colours, 51) == ['first', 'second', 'third']
    with pytest.raises(ValueError):
        missing_colours(img, colours, 0)


def test_render_area_of_a_screen_without_rviz_is_empty():
    blank = np.full((100, 100, 3), 255, dtype=np.uint8)
    assert render_area(blank).size == 0


@pytest.mark.parametrize('rgb, tolerance, expected', [
    ((1.0, 1.0, 1.0), 0, 2), ((0.0, 0.0, 0.0), 0, 1), ((0.0, 0.0, 0.0), 12, 2),
])
def test_colour_pixels(rgb, tolerance, expected):
    img = np.array([[[255, 255, 255], [0, 0, 0], [10, 10, 10], [255, 255, 255]]],
                   dtype=np.uint8)
    assert colour_pixels(img, rgb, tolerance) == expected


@pytest.mark.parametrize('kwargs, robots, labels, expected', [
    ({'robots': 3, 'text_px': 3 * MIN_TEXT_PIXELS}, 3, 3, True),
    ({'robots': 3, 'text_px': 3 * MIN_TEXT_PIXELS}, 4, 3, False),   # a robot missing
    ({'robots': 3, 'text_px': 2 * MIN_TEXT_PIXELS}, 3, 3, False),   # a name missing
    ({'robots': 3, 'text_px': 0}, 3, 0, True),
    # trixie's rviz draws text greyer than bookworm's; a dim grey (the grid's) is not text.
    ({'robots': 3, 'text_px': 3 * MIN_TEXT_PIXELS, 'text_grey': 225}, 3, 3, True),
    ({'robots': 3, 'text_px': 3 * MIN_TEXT_PIXELS, 'text_grey': 100}, 3, 3, False),
    ({'robots': 3, 'text_px': 90, 'arena': False}, 3, 3, False),    # no arena yet
    ({'robots': 0, 'text_px': 0}, 0, 0, True),
    # The white panel outside the view does not count as text.
    ({'robots': 2, 'text_px': 0, 'white_panel': True}, 2, 1, False),
])
def test_shows_lesson(kwargs, robots, labels, expected):
    assert shows_lesson(screen(**kwargs), robots, labels) is expected


def test_shows_lesson_without_a_view():
    assert shows_lesson(np.full((50, 50, 3), 255, dtype=np.uint8), 0, 0) is False


@pytest.mark.parametrize('robots, labels', [(-1, 0), (0, -1)])
def test_shows_lesson_rejects_negative_counts(robots, labels):
    with pytest.raises(ValueError):
        shows_lesson(screen(), robots, labels)


def test_error_lines_skip_debian_noise_only():
    log = '\n'.join([
        '[ INFO] [1.0]: rviz version 1.14.19',
        '[rospack] Error: no such package media_export',
        '[librospack]: error while executing command',
        '[ERROR] [2.0]: Could not load display: rviz/Bogus',
        '[ WARN] [3.0]: something',
        '[FATAL] [4.0]: gone',
    ])
    assert error_lines(log) == ['[ERROR] [2.0]: Could not load display: rviz/Bogus',
                                '[FATAL] [4.0]: gone']
