"""numba's compiler for the model's kernels, or plain Python where numba is missing (no rospy).

python3-numba is a dependency: without it the kernels run as the Python they are written in,
the same numbers many times slower. Every kernel is compiled with cache=True: numba keeps it
in its cache (__pycache__ beside the source, or NUMBA_CACHE_DIR) and warmup.py compiles them
all at ./ws build, first dropping the whole cache when any source of the package changed
(numba checks a kernel against its own file only, not the files of the kernels it calls).
"""
import os

# The threads of the parallel kernels sleep when idle: at real time stageros waits about
# 100 ms between steps, and OpenMP's default (spinning up to 300 000 times first, about 10 ms
# here) would burn part of a core meanwhile. Read by OpenMP when numba first starts its
# threads.
_POLICY_GIVEN = 'OMP_WAIT_POLICY' in os.environ
os.environ.setdefault('OMP_WAIT_POLICY', 'PASSIVE')


def spin_between_kernels():
    """For a run flat out that has the cores to itself (Stage's own `stage -g`): numba's
    threads wait for the next parallel kernel spinning a while (OpenMP's default), not
    asleep: waking them costs about 0.15 ms a kernel on this project's machines, a tenth of
    a flocking world's step, and such a run has no idle time for the spin to waste. Call it
    before the first parallel kernel runs; a policy the user set stays."""
    if not _POLICY_GIVEN:
        os.environ.pop('OMP_WAIT_POLICY', None)

try:
    from numba import get_num_threads as numba_threads
    from numba import njit, prange
except ImportError:  # pragma: no cover - python3-numba is a dependency
    prange = range

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

    def numba_threads():
        return 1

__all__ = ['njit', 'numba_threads', 'prange', 'spin_between_kernels']
