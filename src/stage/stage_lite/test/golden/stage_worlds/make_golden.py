#!/usr/bin/env python3
"""Keep what tests need of stage_capture's runs of Stage's own worlds, one .npz per world.

usage: make_golden.py CAPTURES OUT [--prefix-steps N] [--world NAME..] [--add]

CAPTURES holds one folder per world (capture_worlds.sh's OUT), each with run<k>.stgcap.
For each world it writes OUT/<world>.npz and prints a JSON line of its summary; with --add,
the captures' runs are added after those OUT/<world>.npz holds already (the same world and
states; the parting steps then found again over every run's float64 prefix, so a parting
after the prefix is not seen; the flag counts of every model that held a flag in either),
and meta's `batches` says how many runs each capture gave:

- meta: a JSON string: the capture header (models, interval_sim, threads, seeds), the
  runs, the parting steps (first state where two runs put a robot more than 1 cm, and more
  than 1e-9 m, apart), the sources and sinks found by name;
- prefix_pose: float64 (runs, N + 1, robots, 3), the first N steps' world poses, bit for bit;
- pose: float32 (runs, states, robots, 3) at every `pose_every`-th state (meta says which);
- stall: the stall flags of every state, np.packbits of (runs, states, robots) along robots;
- flags: uint16 (runs, states, F) flag counts of the flag models that ever held a flag;
- stat_<name>: float32 (runs, times) swarm statistics every second (stat_t_s the times).

Run it under /usr/bin/python3 with the workspace sourced (it imports stage_lite.testing).
"""
import argparse
import glob
import json
import os
import sys

import numpy as np
from stage_lite.testing import stage_capture_file, swarm_stats

FLOCKING = {'pioneer_flocking', 'SFU'}
FORAGING = {'fasr', 'fasr2'}
#: Worlds so large that only a short float64 prefix is kept (hospital: 1000 robots).
SHORT_PREFIX = {'benchmark_hospital': 10}
#: Robots above which the float32 poses are kept once a second, not every step.
DENSE_ROBOTS = 10
STAT_EVERY_S = 1.0


def load_runs(folder):
    paths = sorted(glob.glob(os.path.join(folder, 'run*.stgcap')),
                   key=lambda p: int(os.path.basename(p)[3:-7]))
    runs = [stage_capture_file.load(p) for p in paths]
    if not runs:
        raise SystemExit('no runs in %s' % folder)
    n = min(len(a['t_s']) for _, a in runs)
    return paths, runs, n


def places(header):
    """Sources and sinks of a foraging world: its top-level models named *source, *sink."""
    out = {}
    for name, pose in zip(header['flag_models'], header['flag_model_poses'], strict=True):
        for kind in ('source', 'sink'):
            if name.endswith(kind):
                out.setdefault(kind, []).append(pose[:2])
    return {k: np.array(v) for k, v in out.items()}


def same_model_order(world, labels, headers):
    """Warns (on stderr) of runs whose model order differs from the first's: a command line
    of another length moves Stage's models (README, "The model order of each world")."""
    orders = [h.get('model_order') for h in headers]
    odd = [label for label, order in zip(labels, orders, strict=True)
           if order is not None and orders[0] is not None and order != orders[0]]
    if odd:
        print('%s: the model order of %s differs from %s\'s' % (world, ', '.join(odd), labels[0]),
              file=sys.stderr)
    return not odd


def make(world, folder, out_dir, prefix_steps, add=False):
    paths, runs, n = load_runs(folder)
    header = runs[0][0]
    same_model_order(world, [os.path.basename(p) for p in paths], [h for h, _ in runs])
    t_s = runs[0][1]['t_s'][:n]
    poses = [a['pose'][:n] for _, a in runs]
    n_robots = poses[0].shape[1]
    dt = float(np.diff(t_s).min())
    prefix = min(SHORT_PREFIX.get(world, prefix_steps), n - 1)
    pose_every = 1 if n_robots <= DENSE_ROBOTS else int(round(1.0 / dt))
    kinds = places(header) if world in FORAGING else {}
    times = np.arange(0.0, t_s[-1] + dt / 4, STAT_EVERY_S)
    stats = [swarm_stats.swarm_stats(t_s, p, times, flocking=world in FLOCKING,
                                     places=kinds) for p in poses]
    flags = np.stack([a['flags'][:n] for _, a in runs])
    held = np.nonzero(flags.max(axis=(0, 1)) > 0)[0]
    flag_names = [header['flag_models'][i] for i in held]
    stat = {'stat_' + k: np.stack([s[k] for s in stats]).astype(np.float32)
            for k in stats[0] if k != 't_s'}
    # Flags delivered: what each sink holds beyond what it held at the start.
    sinks = [i for i, name in enumerate(header['flag_models']) if name.endswith('sink')]
    if world in FORAGING and sinks:
        idx = swarm_stats.state_index(t_s, times)
        got = flags[:, idx][:, :, sinks].astype(np.int64) - flags[:, :1, sinks]
        stat['stat_delivered_per_sink'] = got.mean(axis=2).astype(np.float32)
    parting = {}
    if len(poses) > 1:
        for label, tol in (('1cm', 0.01), ('1e-9', 1e-9)):
            parting[label] = swarm_stats.parting_step(poses, tol_m=tol)
    meta = dict(header, world_name=world, runs=[os.path.basename(p) for p in paths],
                seeds=[h['drand48_seed_time'] for h, _ in runs], states=n,
                prefix_steps=prefix, pose_every=pose_every, parting_state=parting,
                kept_flag_models=flag_names,
                places={k: v.tolist() for k, v in kinds.items()})
    arrays = dict(
        meta=np.array(json.dumps(meta)),
        prefix_pose=np.stack([p[:prefix + 1] for p in poses]),
        pose=np.stack([p[::pose_every] for p in poses]).astype(np.float32),
        stall=np.packbits(np.stack([a['stall'][:n] for _, a in runs]), axis=2),
        flags=flags[:, :, held].astype(np.uint16),
        stat_t_s=times.astype(np.float32),
        **stat)
    path = os.path.join(out_dir, world + '.npz')
    if add:
        arrays = added_runs(dict(np.load(path)), arrays)
    np.savez_compressed(path, **arrays)
    return summary_of(world, arrays, path)


def added_runs(old, new):
    """The arrays of a world's .npz with the runs of `new` after those of `old`."""
    meta_old, meta_new = (json.loads(str(a['meta'])) for a in (old, new))
    for key in ('world_name', 'states', 'prefix_steps', 'pose_every', 'position_models',
                'flag_models'):
        if meta_old[key] != meta_new[key]:
            raise SystemExit('%s: %s differs: %r against %r'
                             % (meta_new['world_name'], key, meta_old[key], meta_new[key]))
    same_model_order(meta_new['world_name'], ['the npz', 'the added capture'],
                     [meta_old, meta_new])
    # flags: the columns of the models that ever held one in either capture (a model that
    # never did in one held none there)
    kept = [name for name in meta_old['flag_models']
            if name in meta_old['kept_flag_models'] or name in meta_new['kept_flag_models']]
    arrays = {k: (old[k] if k == 'stat_t_s' else np.concatenate([old[k], new[k]]))
              for k in old if k not in ('meta', 'flags')}
    arrays['flags'] = np.concatenate([_flag_columns(a['flags'], m['kept_flag_models'], kept)
                                      for a, m in ((old, meta_old), (new, meta_new))])
    prefix = list(arrays['prefix_pose'])
    meta = dict(meta_old, runs=meta_old['runs'] + ['added/' + r for r in meta_new['runs']],
                kept_flag_models=kept,
                seeds=meta_old['seeds'] + meta_new['seeds'],
                batches=meta_old.get('batches', [len(meta_old['runs'])]) + [len(meta_new['runs'])],
                parting_state={label: swarm_stats.parting_step(prefix, tol_m=tol)
                               for label, tol in (('1cm', 0.01), ('1e-9', 1e-9))})
    arrays['meta'] = np.array(json.dumps(meta))
    return arrays


def _flag_columns(flags, names, kept):
    """flags (runs, states, len(names)) as columns of the models `kept`, 0 for the others."""
    out = np.zeros(flags.shape[:2] + (len(kept),), flags.dtype)
    for k, name in enumerate(names):
        out[:, :, kept.index(name)] = flags[:, :, k]
    return out


def summary_of(world, arrays, path):
    """The JSON line printed for a world's .npz."""
    meta = json.loads(str(arrays['meta']))
    times = arrays['stat_t_s']
    stat = {k: v for k, v in arrays.items() if k.startswith('stat_') and k != 'stat_t_s'}
    dt = meta['interval_sim_us'] / 1e6
    return dict(world=world, robots=arrays['prefix_pose'].shape[2], runs=len(meta['runs']),
                states=meta['states'], dt=dt, parting=meta['parting_state'],
                bytes=os.path.getsize(path),
                stats={k[5:]: [[float(np.min(v[:, i])), float(np.max(v[:, i]))]
                               for i in range(0, len(times), 5)]
                       for k, v in stat.items()},
                stat_times=times[::5].astype(np.float64).tolist())


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('captures')
    parser.add_argument('out')
    parser.add_argument('--prefix-steps', type=int, default=100)
    parser.add_argument('--world', nargs='*')
    parser.add_argument('--add', action='store_true',
                        help="add the captures' runs to OUT/<world>.npz's")
    args = parser.parse_args(argv)
    worlds = args.world or sorted(os.listdir(args.captures))
    for folder in worlds:
        # capture_worlds.sh names a folder for the world file it ran: NAME_run is NAME with
        # `paused 0`, benchmark_NAME is benchmark/NAME.
        world = folder[:-len('_run')] if folder.endswith('_run') else folder
        summary = make(world, os.path.join(args.captures, folder), args.out, args.prefix_steps,
                       args.add)
        print(json.dumps(summary))
        sys.stdout.flush()


if __name__ == '__main__':
    main()
