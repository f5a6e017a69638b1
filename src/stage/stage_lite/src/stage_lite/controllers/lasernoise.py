"""Stage's `lasernoise` (examples/ctrl/lasernoise.cc), on a ranger: after each update, every
range of its first sensor is multiplied by an approximately normal factor of mean 1 and
deviation 0.05 (the sum of 12 rand() / (RAND_MAX + 1) draws, minus 6), before anyone reads
the scan."""
import numpy as np

DEVIATION = 0.05
DRAWS = 12


def init(model, args):
    if model.type != 'ranger':
        raise TypeError('lasernoise goes on a ranger, not a %s' % model.type)
    model.add_callback('update', _noisy)
    model.subscribe()


def _noisy(ranger, _):
    sensors = ranger.sensors
    if not sensors:
        return False
    scan = sensors[0].ranges
    if len(scan):
        draws = ranger.world.random_block(DRAWS * len(scan)).reshape(len(scan), DRAWS)
        # summed in order, as the C loop adds them
        total = np.zeros(len(scan))
        for k in range(DRAWS):
            total += draws[:, k] / (2.0 ** 31)
        scan *= DEVIATION * (total - 6.0) + 1.0
    return False
