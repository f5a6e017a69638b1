"""The beam rule Stage's wander and fasr share (examples/ctrl/wander.cc, fasr.cc), each with
its own middle part and distances: something nearer than `front` in the middle beams, from
n/part to n - n/part exclusive (integer division), is an obstruction; anything nearer than
`stop` anywhere stops the robot; the left half is i > n/2, the right half the rest. Not a
controller itself (no init)."""
import numpy as np

from stage_lite.model.jit import njit


def beam_rule(scan, part, front, stop):
    """(obstruction ahead, something too close, nearest on the left, nearest on the
    right) of a scan."""
    obstruction, too_close, min_left, min_right = _beam_rule(
        np.asarray(scan, np.float64), part, front, stop)
    return bool(obstruction), bool(too_close), min_left, min_right


@njit(cache=True)
def _beam_rule(scan, part, front, stop):
    n = scan.shape[0]
    obstruction = False
    too_close = False
    min_left = 1e6
    min_right = 1e6
    for i in range(n):
        r = scan[i]
        if i > n // part and i < n - n // part and r < front:
            obstruction = True
        if r < stop:
            too_close = True
        if i > n // 2:
            min_left = min(min_left, r)
        else:
            min_right = min(min_right, r)
    return obstruction, too_close, min_left, min_right
