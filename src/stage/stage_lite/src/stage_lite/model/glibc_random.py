"""The C library's random numbers as Stage draws them: glibc's random()/rand() and drand48().

Stage and its controllers draw from two process-wide streams, and a run repeats Stage's only
if every draw comes from the same stream in the same order:
- random() and rand() are one stream (glibc's rand() returns random()): the additive
  feedback generator of degree 31 (TYPE_3), seeded with 1 unless srandom() is called. Stage
  draws it for each thread-safe model it starts (its worker queue), for each ranger beam (its
  noise, even when the noise is zero) and in the controllers (wander's avoid turns, fasr's
  tasks, lasernoise);
- drand48() is the 48-bit linear congruential generator; Stage seeds it from the clock at
  start-up (Stg::Init), so what it draws (random colours, odometry errors, dynamic's poses,
  pioneer_flocking's turns) differs from run to run in Stage; here it is seeded from the
  world's seed.
"""
import numpy as np

from .jit import kernel

RAND_MAX = 2 ** 31 - 1
_DEGREE, _SEPARATION = 31, 3
_M32 = 0xFFFFFFFF


class Random:
    """glibc's random()/rand() stream (TYPE_3); a new one is srandom(1)'s, as an unseeded
    process's. Its state is two numpy arrays (`table`, `pointers`: front, rear) so that the
    model's kernels draw from the same stream (noise.py)."""

    def __init__(self, seed=1):
        self.table = np.zeros(_DEGREE, np.int64)
        self.pointers = np.zeros(2, np.int64)
        self.srandom(seed)

    def srandom(self, seed):
        """glibc's srandom: seed 0 counts as 1; the table filled by 16807 * x mod (2^31 - 1)
        (Schrage's form, on signed 32-bit words), then 310 draws discarded."""
        seed &= _M32
        word = _signed32(seed if seed else 1)
        self.table[0] = word & _M32
        for i in range(1, _DEGREE):
            hi = int(word / 127773)            # C's division truncates toward zero
            lo = word - hi * 127773
            word = 16807 * lo - 2836 * hi
            if word < 0:
                word += RAND_MAX
            self.table[i] = word
        self.pointers[:] = (_SEPARATION, 0)
        for _ in range(10 * _DEGREE):
            self.random()

    def random(self):
        """The next value in [0, RAND_MAX]."""
        table, pointers = self.table, self.pointers
        f, r = int(pointers[0]), int(pointers[1])
        value = (int(table[f]) + int(table[r])) & _M32
        table[f] = value
        pointers[0] = (f + 1) % _DEGREE
        pointers[1] = (r + 1) % _DEGREE
        return value >> 1

    rand = random  # glibc's rand() is random()

    def block(self, count):
        """The next `count` values, in order (int64 array)."""
        out = np.empty(int(count), np.int64)
        _fill(self.table, self.pointers, out)
        return out

    def state(self):
        """A copy of the state, to compare or restore."""
        return self.table.copy(), self.pointers.copy()


class Rand48:
    """The drand48() stream: x <- (0x5DEECE66D * x + 0xB) mod 2^48; srand48(seed) sets the
    high 32 bits to seed and the low 16 to 0x330E. Unseeded, glibc's x is 0. The state is a
    one-element uint64 array (`state`) so that kernels draw from it too (drand48_next)."""

    _A, _C, _M = 0x5DEECE66D, 0xB, (1 << 48) - 1

    def __init__(self, seed=None):
        self.state = np.zeros(1, np.uint64)
        if seed is not None:
            self.srand48(seed)

    def srand48(self, seed):
        self.state[0] = ((seed & _M32) << 16) | 0x330E

    def drand48(self):
        """The next value in [0, 1): the 48 bits as a double's mantissa."""
        x = (self._A * int(self.state[0]) + self._C) & self._M
        self.state[0] = x
        return x / float(1 << 48)


@kernel
def drand48_next(state):
    """Rand48.drand48 in a kernel, on its state array (uint64 arithmetic wraps mod 2^64,
    of which 2^48 is a divisor)."""
    x = (state[0] * np.uint64(0x5DEECE66D) + np.uint64(0xB)) & np.uint64((1 << 48) - 1)
    state[0] = x
    return x / float(1 << 48)


@kernel
def random_next(table, pointers):
    """Random.random in a kernel, on its state arrays (table, pointers)."""
    f = pointers[0]
    r = pointers[1]
    value = (table[f] + table[r]) & 0xFFFFFFFF
    table[f] = value
    pointers[0] = (f + 1) % 31
    pointers[1] = (r + 1) % 31
    return value >> 1


@kernel
def _fill(table, pointers, out):
    for k in range(out.shape[0]):
        out[k] = random_next(table, pointers)


def _signed32(value):
    value &= _M32
    return value - (1 << 32) if value & 0x80000000 else value
