#!/usr/bin/python3
"""Turn stage_probe runs of the real Stage on worlds/draws.world into data/draws.npz.

    make_draws.py OUT.npz RUN1.txt RUN2.txt ...

Each RUN is what `stage -g` printed with probe/stage_probe.so on the world (see
probe/stage_probe.cc). The .npz keeps, per run r, per step k (t = (k + 1) * 100 ms):
scan_hits[r, k, s] and scan_sum[r, k, s] of each ranger s (`rangers`, in order), pose[r, k,
p] (x, y, a) and stall[r, k, p] of each robot p (`robots`), rng[r, k] (random()'s 31 words).
Run by hand (not installed, not part of ./ws test).
"""
import sys

import numpy as np


def parse(path):
    scans, poses, rng = {}, {}, {}
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == 'SCAN':
                scans[(int(p[1]), p[2])] = (int(p[3]), float(p[4]))
            elif p[0] == 'POSE':
                poses[(int(p[1]), p[2])] = (float(p[3]), float(p[4]), float(p[5]), int(p[6]))
            elif p[0] == 'RNG':
                rng[int(p[1])] = [int(x) for x in p[2:]]
    return scans, poses, rng


def main(out, paths):
    runs = [parse(p) for p in paths]
    times = sorted(set.intersection(*(set(rng) for _, _, rng in runs)))
    rangers = sorted({tok for s, _, _ in runs for _, tok in s}, key=lambda t: t)
    robots = sorted({tok for _, p, _ in runs for _, tok in p})
    shape = (len(runs), len(times))
    arrays = dict(
        t_us=np.array(times, np.int64), rangers=np.array(rangers), robots=np.array(robots),
        scan_hits=np.zeros(shape + (len(rangers),), np.int32),
        scan_sum=np.zeros(shape + (len(rangers),), np.float64),
        pose=np.zeros(shape + (len(robots), 3), np.float64),
        stall=np.zeros(shape + (len(robots),), np.bool_),
        rng=np.zeros(shape + (31,), np.uint32))
    for r, (scans, poses, rng) in enumerate(runs):
        for k, t in enumerate(times):
            for s, tok in enumerate(rangers):
                arrays['scan_hits'][r, k, s], arrays['scan_sum'][r, k, s] = scans[(t, tok)]
            for p, tok in enumerate(robots):
                x, y, a, stall = poses[(t, tok)]
                arrays['pose'][r, k, p] = (x, y, a)
                arrays['stall'][r, k, p] = stall
            arrays['rng'][r, k] = rng[t]
    np.savez_compressed(out, **arrays)


if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2:])
