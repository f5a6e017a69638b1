"""stage_lite.model.floor: the static bodies' raster shrunk for maps and pictures (coarsen)."""
import numpy as np
import pytest
from stage_lite.model.floor import coarsen


@pytest.mark.parametrize('factor, expected', [
    (1, [[1, 0, 0], [0, 0, 0], [0, 0, 1]]),
    (2, [[1, 0], [0, 1]]),
    (3, [[1]]),
])
def test_coarsen_keeps_any_wall(factor, expected):
    grid = np.array([[1, 0, 0], [0, 0, 0], [0, 0, 1]], bool)
    assert coarsen(grid, factor).astype(int).tolist() == expected


@pytest.mark.parametrize('factor', [0, 1.5, -2])
def test_coarsen_refuses_bad_factors(factor):
    with pytest.raises(ValueError):
        coarsen(np.zeros((2, 2), bool), factor)
