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

from .glibc_random import RAND_MAX, random_next
from .jit import kernel

TWO_PI = math.pi + math.pi


@kernel
def _simple_noise(table, pointers):
    return 2.0 * ((random_next(table, pointers) % 1000) * 0.001 - 0.5)


# spare[0]: no spare (0), a spare ready (COOKED: spare[1] = -2 log(rand1), spare[2] the
# angle), or a spare still as its two draws (RAW: spare[1], spare[2] as random() gave them).
# A beam whose noise has no gaussian part (const 0) only moves the stream: it keeps its
# pair raw, and the logarithm and the angle are worked out only if a noisy beam takes it.
COOKED = 1.0
RAW = 2.0


@kernel
def _cook(spare):
    """A raw spare made ready, with generateGaussianNoise's own operations."""
    if spare[0] == RAW:
        rand1 = spare[1] / RAND_MAX
        if rand1 < 1e-100:
            rand1 = 1e-100
        spare[1] = -2.0 * math.log(rand1)
        spare[2] = (spare[2] / RAND_MAX) * TWO_PI
        spare[0] = COOKED


@kernel
def _next(table, f, r):
    """random_next with the stream's pointers as values: (value, front, rear) after the draw."""
    value = (table[f] + table[r]) & 0xFFFFFFFF
    table[f] = value
    return value >> 1, (f + 1) % 31, (r + 1) % 31


@kernel
def _gaussian_at(table, f, r, spare, variance):
    """generateGaussianNoise(variance) with the stream's pointers as values: (noise, front,
    rear). spare = [have one, rand1, rand2]: the pair's second value kept for the next call.
    With variance 0 the noise is a zero (Stage's sqrt(0 * rand1) times a cosine or sine),
    which adds nothing to a range (ranges are not -0.0): 0.0, the pair left raw."""
    if spare[0] != 0.0:
        if variance == 0.0:
            spare[0] = 0.0
            return 0.0, f, r
        _cook(spare)
        spare[0] = 0.0
        return math.sqrt(variance * spare[1]) * math.sin(spare[2]), f, r
    v1, f, r = _next(table, f, r)
    v2, f, r = _next(table, f, r)
    spare[0] = RAW
    spare[1] = v1
    spare[2] = v2
    if variance == 0.0:
        return 0.0, f, r
    _cook(spare)
    return math.sqrt(variance * spare[1]) * math.cos(spare[2]), f, r


@kernel
def _gaussian(table, pointers, spare, variance):
    """generateGaussianNoise, the stream's pointers in memory (_gaussian_at)."""
    noise, f, r = _gaussian_at(table, pointers[0], pointers[1], spare, variance)
    pointers[0] = f
    pointers[1] = r
    return noise


@kernel
def _apply_rows(table, pointers, spare, ranges, offsets, rows, range_max, proportional,
                constant):
    """The draws of each row's beams (ranges[offsets[i]:offsets[i + 1]]), rows in turn, the
    noise added in place: per beam the angle's draw (no angular noise here), then, for a
    hit, range + range * prop * _simple_noise() + _gaussian(const) (C++ evaluates the sum's
    calls left to right here, GCC: the uniform first); a miss reads range max and draws
    nothing more. The stream's pointers are kept in registers between draws (written back
    at the end), not in memory at every draw: the same draws, in the same order."""
    f = pointers[0]
    r = pointers[1]
    for i in rows:
        rmax = range_max[i]
        prop = proportional[i]
        variance = constant[i]
        for t in range(offsets[i], offsets[i + 1]):
            _, f, r = _next(table, f, r)        # the angle's draw (no angular noise here)
            x = ranges[t]
            if x < rmax:
                v, f, r = _next(table, f, r)
                uniform = 2.0 * ((v % 1000) * 0.001 - 0.5)     # _simple_noise
                gauss, f, r = _gaussian_at(table, f, r, spare, variance)
                ranges[t] = x + x * prop * uniform + gauss
    pointers[0] = f
    pointers[1] = r


class RangerNoise:
    """The draws of every ranger update, from the world's random() stream (glibc_random)."""

    def __init__(self, random):
        self.random = random
        self.spare = np.zeros(3, np.float64)

    def apply(self, ranges, range_max, noise):
        """A sensor's ranges as Sensor::Update leaves them, beams cast without angular noise:
        float64 array; the stream moved as Stage moves it."""
        const, prop, _ = noise
        out = np.array(ranges, np.float64)
        self.apply_rows(out, np.array([0, len(out)], np.int64), np.zeros(1, np.int64),
                        np.array([range_max], np.float64), np.array([prop], np.float64),
                        np.array([const], np.float64))
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
