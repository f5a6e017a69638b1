#!/usr/bin/python3
"""Turn probe/model_dump runs of the real Stage into golden data (run by hand, not
installed, not part of ./ws test).

    make_probe_golden.py dynamic OUT.txt RUN1.txt RUN2.txt ...
    make_probe_golden.py poses OUT.npz RUN1.txt RUN2.txt ...

`dynamic`: one text file: the first run's MODEL and ERROR lines and its POSE lines (every run
gave the same: checked), and per step each distinct SCAN line the runs gave (the rangers run
in a worker thread beside the moves: a scan is cast from the robot's pose before or after
its move). Numbers are written as Python's repr (the shortest text that reads back to the
same double).
`poses`: an .npz of every run's POSE lines: t_us (steps), robots (tokens), pose[run, step,
robot] (x, y, a), stall[run, step, robot].
"""
import sys

import numpy as np


def lines(path, kind):
    with open(path) as f:
        return [line.split() for line in f if line.startswith(kind + ' ')]


def shortest(words):
    return ' '.join(w if _text(w) or w.lstrip('-').isdigit() else repr(float(w)) for w in words)


def _text(word):
    try:
        float(word)
    except ValueError:
        return True
    return False


def dynamic(out, paths):
    poses = [lines(p, 'POSE') for p in paths]
    if any(p != poses[0] for p in poses):
        sys.exit('the runs differ in their poses')
    scans = {}
    for path in paths:
        for words in lines(path, 'SCAN'):
            text = shortest(words)
            seen = scans.setdefault(int(words[1]), [])
            if text not in seen:
                seen.append(text)
    with open(out, 'w') as f:
        f.write('# the real Stage 4.3.0 on test/worlds/<this file\'s name>.world: %d runs of'
                ' probe/model_dump (see ../README.md)\n' % len(paths))
        for kind in ('MODEL', 'ERROR'):
            for words in lines(paths[0], kind):
                f.write(shortest(words) + '\n')
        for words in poses[0]:
            f.write(shortest(words) + '\n')
        for t in sorted(scans):
            for text in scans[t]:
                f.write(text + '\n')


def pose_runs(out, paths):
    runs = [lines(p, 'POSE') for p in paths]
    times = sorted({int(w[1]) for w in runs[0]})
    robots = list(dict.fromkeys(w[2] for w in runs[0]))
    pose = np.zeros((len(runs), len(times), len(robots), 3))
    stall = np.zeros((len(runs), len(times), len(robots)), np.uint8)
    for r, run in enumerate(runs):
        for w in run:
            k, p = times.index(int(w[1])), robots.index(w[2])
            pose[r, k, p] = [float(v) for v in w[3:6]]
            stall[r, k, p] = int(w[6])
    np.savez_compressed(out, t_us=np.array(times, np.int64), robots=np.array(robots),
                        pose=pose, stall=stall)


if __name__ == '__main__':
    {'dynamic': dynamic, 'poses': pose_runs}[sys.argv[1]](sys.argv[2], sys.argv[3:])
