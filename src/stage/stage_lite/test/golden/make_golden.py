#!/usr/bin/python3
"""Turn a capture of real Stage (capture.py) into the golden data stage_lite's tests replay.

    make_golden.py CAPTURE.npz OUT.npz [--embed WORLD_DIR]

Keeps what test_stage_golden.py needs: the steps; per robot the odom twist (the velocity
Stage applied at each step: the replay's commands), the ground-truth and odom poses, and
every scan's ranges and intensities (float32, as published). Adds to the meta the world
file's name (the replay loads it from worlds/ beside this script) and `reset_before`: the
step before which reset_positions took effect (it runs between two steps, in stageros's
service thread): the first step, after the call, at which a robot jumped farther than its
velocity takes it in a step. With --embed, the world file and the files of WORLD_DIR it
names (its bitmaps) go into OUT.npz as they were (`file/NAME` byte arrays, their names in the
meta's `embedded`): for a world that lives in another package (the lesson's, in stage_multi),
which stage_lite's tests cannot depend on. Under /usr/bin/python3 with the workspace sourced
(captures are read by stage_lite.testing.golden, as the tests read them).
"""
import hashlib
import json
import os
import re
import sys

import numpy as np
from stage_lite.testing.golden import load


def reset_step(arrays, meta, robots):
    """The step before which the capture's reset took effect, or None."""
    resets = [a for a in meta.get('actions_done', []) if a.get('reset')]
    if not resets:
        return None
    steps = arrays['steps']
    dt = meta['interval_sim_ms'] / 1000.0
    after = resets[0]['clock_step']
    for row in np.flatnonzero(steps > after):
        for r in robots:
            gt, twist = arrays['r%d_gt_pose' % r], arrays['r%d_odom_twist' % r]
            jump = np.hypot(*(gt[row, :2] - gt[row - 1, :2]))
            if jump > (abs(twist[row, 0]) + abs(twist[row, 1])) * dt + 1e-6:
                return int(steps[row])
    raise SystemExit('make_golden.py: no robot jumps back after the reset call')


def embedded_files(world_dir, world_name, sha1):
    """{name: bytes} of the world file and of every file of world_dir its text quotes."""
    with open(os.path.join(world_dir, world_name), 'rb') as f:
        text = f.read()
    if hashlib.sha1(text).hexdigest() != sha1:
        raise SystemExit('make_golden.py: %s is not the captured world (sha1 differs)'
                         % world_name)
    files = {world_name: text}
    for name in re.findall(rb'"([^"]+)"', text):
        path = os.path.join(world_dir, name.decode())
        if os.path.isfile(path):
            with open(path, 'rb') as f:
                files[os.path.basename(path)] = f.read()
    return files


def main():
    src, out = sys.argv[1:3]
    embed_dir = sys.argv[sys.argv.index('--embed') + 1] if '--embed' in sys.argv else None
    arrays, meta = load(src)
    robots = sorted({int(k[1:k.index('_')]) for k in arrays if k.startswith('r')})
    keep = {'steps': arrays['steps']}
    for key, value in arrays.items():
        if key.startswith('r') and key.endswith(('_odom_twist', '_gt_pose', '_odom_pose',
                                                 '_ranges', '_intensities')):
            keep[key] = value
    golden_meta = {
        'world': os.path.basename(meta['world']), 'world_sha1': meta['world_sha1'],
        'captured': meta['date'], 'gui': meta['gui'], 'stage_commit': meta['stage_commit'],
        'stage_ros_commit': meta['stage_ros_commit'], 'script': meta['script'],
        'actions_done': meta['actions_done'], 'reset_before': reset_step(arrays, meta, robots)}
    if embed_dir is not None:
        files = embedded_files(embed_dir, golden_meta['world'], meta['world_sha1'])
        golden_meta['embedded'] = sorted(files)
        for name, data in files.items():
            keep['file/' + name] = np.frombuffer(data, np.uint8)
    np.savez_compressed(out, meta=json.dumps(golden_meta), **keep)
    print('%s: %d steps, %d robots, reset before step %s'
          % (out, len(keep['steps']), len(robots), golden_meta['reset_before']))


if __name__ == '__main__':
    main()
