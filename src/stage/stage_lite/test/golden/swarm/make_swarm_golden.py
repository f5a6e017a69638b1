#!/usr/bin/env python3
"""The swarm test's golden data from make_golden.py's .npz of the real Stage's runs of
stage_lite.swarm_world.world_text(N) (see README.md here).

usage: make_swarm_golden.py CAPTURED_NPZ WORLD_FILE OUT_NPZ [CAPTURE_STGCAP]

Keeps, of the runs: the states every run agrees on to the bit (from the float64 prefix:
state 0, after loading, up to the last state before any two runs differ in any pose), the
swarm statistics of every run once a second, the world file's sha256, so that a test
knows the data are of the world it builds, and Stage's model order of the runs (from the
captures' header, or from CAPTURE_STGCAP's: a capture by the same command line).
"""
import hashlib
import json
import sys

import numpy as np
from stage_lite.testing import stage_capture_file


def main(argv=None):
    args = sys.argv[1:] if argv is None else argv
    if len(args) not in (3, 4):
        sys.exit('usage: make_swarm_golden.py CAPTURED.npz WORLD OUT.npz [CAPTURE.stgcap]')
    captured, world_file, out = args[:3]
    data = np.load(captured)
    meta = json.loads(str(data['meta']))
    prefix = data['prefix_pose']
    agree = 0
    while agree + 1 < prefix.shape[1] and (prefix[:, agree + 1] == prefix[0, agree + 1]).all():
        agree += 1
    with open(world_file, 'rb') as f:
        sha = hashlib.sha256(f.read()).hexdigest()
    small = dict(runs=len(meta['runs']), seeds=meta['seeds'], states=meta['states'],
                 interval_sim_us=meta['interval_sim_us'], threads=meta['threads'],
                 agree_through_state=agree, world_sha256=sha)
    # Stage's model order for the capture's command line (stage_capture's header has it;
    # a capture made before it did can give it from a run of the same command)
    order = meta.get('model_order')
    if len(args) == 4:
        order = stage_capture_file.load(args[3])[0]['model_order']
    if order is not None:
        small['model_order'] = order
    stats = {k: data[k] for k in data.files if k.startswith('stat_')}
    np.savez_compressed(out, meta=np.array(json.dumps(small)), agreed=prefix[0, :agree + 1],
                        **stats)
    print(json.dumps(small))


if __name__ == '__main__':
    main()
