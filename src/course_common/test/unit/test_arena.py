"""Unit tests of course_common.arena: turtlesim's world size, centre and spawn point."""
import struct
import subprocess
import sys

import pytest
from course_common.arena import CANVAS_PX, CENTRE_M, METER_PX, SPAWN_M, WORLD_SIZE_M, inside

TOL = 1e-12  # m: the constants are closed-form


def _f32(value):
    return struct.unpack('f', struct.pack('f', value))[0]


def test_constants_are_turtlesims():
    assert (CANVAS_PX, METER_PX) == (500, 45.0)
    assert pytest.approx(11.088889, abs=1e-6) == WORLD_SIZE_M   # as turtlesim prints it
    assert pytest.approx(499.0 / 45.0, abs=TOL) == WORLD_SIZE_M
    assert pytest.approx(WORLD_SIZE_M / 2.0, abs=TOL) == CENTRE_M
    assert _f32(5.5444446) == SPAWN_M                             # float32, as turtlesim spawns
    assert abs(SPAWN_M - CENTRE_M) < 1e-6


def test_no_numpy():
    # Tools and lesson models import the arena without the simulator's numpy.
    code = 'import sys, course_common.arena; sys.exit("numpy" in sys.modules)'
    assert subprocess.run([sys.executable, '-c', code], check=False).returncode == 0


@pytest.mark.parametrize('x, y, size, expected', [
    (0.0, 0.0, WORLD_SIZE_M, True),
    (WORLD_SIZE_M, WORLD_SIZE_M, WORLD_SIZE_M, True),   # the walls count as inside
    (SPAWN_M, SPAWN_M, WORLD_SIZE_M, True),
    (-0.01, 5.0, WORLD_SIZE_M, False),
    (5.0, WORLD_SIZE_M + 0.01, WORLD_SIZE_M, False),
    (3, 3, 2, False),
    (1, 1, 2, True),
])
def test_inside(x, y, size, expected):
    assert inside(x, y, size) is expected


@pytest.mark.parametrize('x, y, size, word', [
    (float('nan'), 1.0, WORLD_SIZE_M, 'x = nan'),
    (1.0, None, WORLD_SIZE_M, 'y = None'),
    (1.0, 1.0, float('inf'), 'size_m = inf'),
    (1.0, 1.0, 0.0, 'size_m = 0.0: expected a finite number > 0'),
    (1.0, 1.0, -2, 'size_m = -2'),
])
def test_inside_refuses_bad_numbers(x, y, size, word):
    with pytest.raises(ValueError, match=word.replace('(', r'\(')):
        inside(x, y, size)
