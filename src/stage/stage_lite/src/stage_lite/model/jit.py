"""numba's compiler for the model's kernels, or plain Python where numba is missing (no rospy).

python3-numba is a dependency: without it the kernels run as the Python they are written in,
the same numbers many times slower. Every kernel is compiled with cache=True: numba keeps it
in its cache (__pycache__ beside the source, or NUMBA_CACHE_DIR) and warmup.py compiles them
all at ./ws build, first dropping the whole cache when any source of the package changed
(numba checks a kernel against its own file only, not the files of the kernels it calls).
"""
import os

import numpy as np

# The threads of the parallel kernels sleep when idle, in every program: at real time
# stageros waits about 100 ms between steps, and OpenMP's default (spinning up to 300 000
# times first, about 10 ms here) would burn part of a core meanwhile; flat out (`stage -g`)
# the spinning thread took a core from the robots' moves on their second thread and, on a
# busy host, from the main thread too (side by side: pioneer_flocking, cave, hospital and
# 10,000 swarmbots 1.1 to 2 times as fast asleep). Read by OpenMP when it is first loaded;
# a policy the user set stays.
os.environ.setdefault('OMP_WAIT_POLICY', 'PASSIVE')

try:
    from numba import get_num_threads as numba_threads
    from numba import njit, prange
except ImportError:  # pragma: no cover - python3-numba is a dependency
    prange = range

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

    def numba_threads():
        return 1


def kernel(fn=None, **options):
    """numba's njit(cache=True, **options) without its reference counting, for a kernel that
    creates no array and returns none.

    numba counts the references to every array a kernel hands to another (an atomic add and
    an atomic subtract per array per call, where it cannot prove them useless): a kernel
    called per robot or per block with 30 to 60 arrays spent most of its time there (the
    hospital's moves, 0.8 of their 2.1 ms a step). The caller keeps the arrays alive anyway.
    A kernel that would create an array does not compile with it (a typing error at
    ./ws build); one that returned a view of an array must keep njit.
    """
    decorate = njit(cache=True, _nrt=False, **options)
    return decorate if fn is None else decorate(fn)


#: A kernel's array index as numba takes it without a test, for an index that is never
#: negative: numba tests every signed index for a negative value (which counts from the end,
#: as in Python) and takes an unsigned one as it is. In the grid's loops over a body's cells
#: those tests were half of each cell's cost (grid.py).
unsigned = np.uint64

__all__ = ['kernel', 'njit', 'numba_threads', 'prange', 'unsigned']
