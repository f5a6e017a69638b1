"""Unit tests of course_common.rviz.colours: the lesson markers' colours."""

import pytest
from course_common.rviz.colours import ARENA_RGB, PALETTE, robot_color


@pytest.mark.parametrize('index, expected', [
    (0, PALETTE[0]), (1, PALETTE[1]), (len(PALETTE), PALETTE[0]), (len(PALETTE) + 2, PALETTE[2]),
])
def test_robot_color_cycles(index, expected):
    assert robot_color(index) == expected


def test_palette_is_distinct_and_not_the_arena():
    assert len(set(PALETTE)) == len(PALETTE)
    assert ARENA_RGB not in PALETTE


@pytest.mark.parametrize('index', [-1, 1.0, None, True])
def test_robot_color_rejects_bad_index(index):
    with pytest.raises(ValueError, match='robot index'):
        robot_color(index)
