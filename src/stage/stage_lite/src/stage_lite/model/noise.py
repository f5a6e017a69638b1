"""Stage 4.3's ranger noise, and the random numbers every ranger update draws (no rospy).

A sensor's `noise [const prop angular]` (model_ranger.cc, Sensor::Update), beam by beam:
1. the beam's angle is turned by increment * angular * simpleNoise() * 0.5, where
   simpleNoise() = 2 * (rand() % 1000 * 0.001 - 0.5), uniform in [-1, 1) in steps of 0.002:
   drawn for every beam, even with no angular noise (then it turns nothing);
2. a beam that hits (range < range max) reads range + range * prop * simpleNoise() +
   gaussian(const), gaussian being Box-Muller on two rand() / RAND_MAX draws whose second
   value is kept for the next call (one spare for the whole process: every sensor's beams
   share it); a miss reads range max and draws nothing more.
So every ranger update moves glibc's random() stream, noise or not, and the controllers that
draw from it (wander's avoid turns) see where the rangers left it. The draws come after the
beam's cast; without angular noise the cast does not depend on them, so the world casts a
step's beams together and draws here in Stage's order.
"""
import math

import numpy as np

from .glibc_random import RAND_MAX
from .jit import njit

TWO_PI = math.pi + math.pi


@njit(cache=True)
def _random(table, pointers):
    f = pointers[0]
    r = pointers[1]
    value = (table[f] + table[r]) & 0xFFFFFFFF
    table[f] = value
    pointers[0] = (f + 1) % 31
    pointers[1] = (r + 1) % 31
    return value >> 1


@njit(cache=True)
def _simple_noise(table, pointers):
    return 2.0 * ((_random(table, pointers) % 1000) * 0.001 - 0.5)


@njit(cache=True)
def _gaussian(table, pointers, spare, variance):
    """generateGaussianNoise: spare = [have one, rand1, rand2]."""
    if spare[0] != 0.0:
        spare[0] = 0.0
        return math.sqrt(variance * spare[1]) * math.sin(spare[2])
    spare[0] = 1.0
    rand1 = _random(table, pointers) / RAND_MAX
    if rand1 < 1e-100:
        rand1 = 1e-100
    rand1 = -2.0 * math.log(rand1)
    spare[1] = rand1
    spare[2] = (_random(table, pointers) / RAND_MAX) * TWO_PI
    return math.sqrt(variance * rand1) * math.cos(spare[2])


@njit(cache=True)
def _apply(table, pointers, spare, ranges, range_max, proportional, constant, out):
    for t in range(ranges.shape[0]):
        _simple_noise(table, pointers)      # the angle's draw (no angular noise here)
        r = ranges[t]
        if r < range_max:
            # C++ evaluates the sum's calls left to right here (GCC): the uniform first
            out[t] = r + r * proportional * _simple_noise(table, pointers) \
                + _gaussian(table, pointers, spare, constant)
        else:
            out[t] = r


@njit(cache=True)
def _apply_rows(table, pointers, spare, ranges, offsets, rows, range_max, proportional,
                constant):
    for i in rows:
        _apply(table, pointers, spare, ranges[offsets[i]:offsets[i + 1]], range_max[i],
               proportional[i], constant[i], ranges[offsets[i]:offsets[i + 1]])


class RangerNoise:
    """The draws of every ranger update, from the world's random() stream (glibc_random)."""

    def __init__(self, random):
        self.random = random
        self.spare = np.zeros(3, np.float64)

    def apply(self, ranges, range_max, noise):
        """A sensor's ranges as Sensor::Update leaves them, beams cast without angular noise:
        float64 array; the stream moved as Stage moves it."""
        const, prop, _ = noise
        out = np.empty(len(ranges), np.float64)
        _apply(self.random.table, self.random.pointers, self.spare,
               np.asarray(ranges, np.float64), float(range_max), float(prop), float(const), out)
        return out

    def apply_rows(self, ranges, offsets, rows, range_max, proportional, constant):
        """apply() on many sensors' beams in one array, in place: the sensors `rows` (their
        beams ranges[offsets[i]:offsets[i + 1]], their range max and noise by row), in the
        order given."""
        _apply_rows(self.random.table, self.random.pointers, self.spare, ranges, offsets,
                    rows, range_max, proportional, constant)

    def angle_noise(self):
        """One beam's angle draw (simpleNoise), for a sensor with angular noise, whose beams
        are cast one at a time."""
        return _simple_noise(self.random.table, self.random.pointers)

    def range_noise(self, r, range_max, noise):
        """One beam's range after its angle draw and its cast."""
        const, prop, _ = noise
        if r < range_max:
            return r + r * prop * _simple_noise(self.random.table, self.random.pointers) \
                + _gaussian(self.random.table, self.random.pointers, self.spare, const)
        return r
