#!/usr/bin/python3
"""Compare two captures of capture.py (real Stage against ours), step by step, beam by beam.

    compare.py REAL.npz OURS.npz [--worst N]

Prints, on the steps both captures hold: per robot and laser, the share of beams whose
ranges are float32-equal and within 5 cm, the share of equal intensities, the worst beams
(beam index, step, real, ours), and each capture's stale scans (a scan identical to the step
before's while the robot moved: real Stage's ranger now and then skips an update, at steps
that change from run to run, and catches up at the next); per robot, the largest odom and
ground-truth pose differences (mm, mrad) and odom twist difference; and each capture's
stall steps (a step whose odom twist, the velocity Stage applied, is non-zero while the
ground-truth pose did not change from the step before) with the steps only one of them
stalls at.
Under /usr/bin/python3 with the workspace sourced (captures are read, and stalls told, by
stage_lite.testing.golden, as the tests read them).
"""
import argparse
import re
import sys

import numpy as np
from stage_lite.testing.golden import load, stall_steps

NEAR_M = 0.05  # "within 5 cm"
WORST = 5  # beams listed per laser


def keys_of(arrays, pattern):
    """{(robot, name): prefix} of the arrays matching pattern (groups: robot, name)."""
    found = {}
    for key in arrays:
        match = re.fullmatch(pattern, key)
        if match:
            found[(int(match.group(1)), match.group(2))] = key
    return found


def percent(mask):
    return '%.2f %%' % (100.0 * np.mean(mask)) if mask.size else 'n/a'


def wrap(angle):
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def scan_rows(a, b, ia, ib, worst):
    """Table rows of every laser both captures have, on their common steps (ia, ib)."""
    rows = []
    lasers_a = keys_of(a, r'r(\d+)_(scan\d+)_ranges')
    lasers_b = keys_of(b, r'r(\d+)_(scan\d+)_ranges')
    for robot, scan in sorted(lasers_a.keys() | lasers_b.keys()):
        if (robot, scan) not in lasers_a or (robot, scan) not in lasers_b:
            rows.append('| r%d | %s | only in %s |||||||' % (
                robot, scan, 'real' if (robot, scan) in lasers_a else 'ours'))
            continue
        prefix = 'r%d_%s_' % (robot, scan)
        ra, rb = a[prefix + 'ranges'][ia], b[prefix + 'ranges'][ib]
        if ra.shape != rb.shape:
            rows.append('| r%d | %s | beams %d vs %d |||||||' % (robot, scan, ra.shape[1],
                                                                 rb.shape[1]))
            continue
        rows_a, rows_b = ~np.isnan(ra).all(axis=1), ~np.isnan(rb).all(axis=1)  # published
        both = rows_a & rows_b
        late = ''.join(' (%s from s%d)' % (name, a['steps'][ia][np.argmax(r)])
                       for name, r in (('real', rows_a), ('ours', rows_b)) if not r.all())
        ra, rb = ra[both], rb[both]
        equal = (ra == rb) | (np.isnan(ra) & np.isnan(rb))
        diff = np.abs(ra.astype(np.float64) - rb.astype(np.float64))
        intensities = a[prefix + 'intensities'][ia][both] == b[prefix + 'intensities'][ib][both]
        geom = 'same' if np.array_equal(a[prefix + 'geom'][ia][both],
                                        b[prefix + 'geom'][ib][both]) else 'DIFFERENT'
        by_beam = np.where(np.isnan(diff), np.inf, diff).max(axis=0)
        listed = []
        for beam in np.argsort(-by_beam)[:worst]:
            if by_beam[beam] == 0:
                break
            step = int(np.argmax(np.where(np.isnan(diff[:, beam]), np.inf, diff[:, beam])))
            listed.append('#%d s%d %.4f/%.4f' % (beam, a['steps'][ia][both][step],
                                                   ra[step, beam], rb[step, beam]))
        stale = ['%d (%s)' % (len(st), spans(st)) if st else '0'
                 for st in (stale_steps(a, robot, scan, ia), stale_steps(b, robot, scan, ib))]
        rows.append('| r%d | %s | %d | %d%s | %s | %s | %s | %s | %s | %s |' % (
            robot, scan, ra.shape[1], len(ra), late, percent(equal), percent(diff <= NEAR_M),
            percent(intensities), geom, ' / '.join(stale), '; '.join(listed) or '-'))
    return rows


def stale_steps(arrays, robot, scan, rows):
    """The steps (among rows of arrays['steps']) whose scan repeats the step before's while
    the robot's ground-truth pose changed."""
    ranges = arrays['r%d_%s_ranges' % (robot, scan)][rows]
    pose = arrays['r%d_gt_pose' % robot][rows]
    stale = np.all(ranges[1:] == ranges[:-1], axis=1) & np.any(pose[1:] != pose[:-1], axis=1)
    return set(arrays['steps'][rows][1:][stale].tolist())


def spans(steps):
    """'3-7, 9' of a set of steps."""
    out, run = [], []
    for s in sorted(steps):
        if run and s != run[-1] + 1:
            out.append(run)
            run = []
        run.append(s)
    if run:
        out.append(run)
    return ', '.join('%d' % r[0] if len(r) == 1 else '%d-%d' % (r[0], r[-1]) for r in out)


def pose_rows(a, b, ia, ib):
    """Table rows of pose, twist and stall differences per robot both captures have."""
    rows = []
    robots = sorted({r for r, _ in keys_of(a, r'r(\d+)_(odom)_pose')}
                    & {r for r, _ in keys_of(b, r'r(\d+)_(odom)_pose')})
    for robot in robots:
        cells = []
        for topic in ('odom', 'gt'):
            pa, pb = a['r%d_%s_pose' % (robot, topic)][ia], b['r%d_%s_pose' % (robot, topic)][ib]
            cells.append('%.3f' % (1000.0 * np.nanmax(np.hypot(*(pa[:, :2] - pb[:, :2]).T))))
            cells.append('%.3f' % (1000.0 * np.nanmax(np.abs(wrap(pa[:, 2] - pb[:, 2])))))
        twist = np.nanmax(np.abs(a['r%d_odom_twist' % robot][ia]
                                 - b['r%d_odom_twist' % robot][ib]))
        stall_a, stall_b = stall_steps(a, robot), stall_steps(b, robot)
        common = set(a['steps'][ia].tolist())
        stall_a, stall_b = stall_a & common, stall_b & common
        rows.append('| r%d | %s | %s | %s | %s | %.4g | %d (%s) | %d (%s) | %s | %s |' % (
            robot, *cells, twist, len(stall_a), spans(stall_a) or '-', len(stall_b),
            spans(stall_b) or '-', spans(stall_a - stall_b) or '-',
            spans(stall_b - stall_a) or '-'))
    return rows


def compare(path_a, path_b, worst=WORST):
    """The report of two captures, as lines of text (markdown tables)."""
    a, meta_a = load(path_a)
    b, meta_b = load(path_b)
    lines = ['%s: %s stageros%s, world %s' % (path, m['stageros'], ' (gui)' if m['gui'] else '',
                                              m['world'])
             for path, m in ((path_a, meta_a), (path_b, meta_b))]
    if meta_a['world_sha1'] != meta_b['world_sha1']:
        lines.append('WARNING: the world files differ (sha1)')
    # a command reaches a stageros when its subscriber has connected: with many robots real
    # Stage may take it steps later, and then poses differ for that reason alone
    steps_a = [x.get('clock_step') for x in meta_a.get('actions_done', [])]
    steps_b = [x.get('clock_step') for x in meta_b.get('actions_done', [])]
    if steps_a != steps_b:
        lines.append('WARNING: the script ran at other steps (real %s, ours %s): differences'
                     ' may come from the inputs alone' % (steps_a, steps_b))
    common, ia, ib = np.intersect1d(a['steps'], b['steps'], return_indices=True)
    lines.append('steps in common: %s (%d); real %d..%d, ours %d..%d' % (
        spans(set(common.tolist())) or 'none', len(common), a['steps'][0], a['steps'][-1],
        b['steps'][0], b['steps'][-1]))
    if not len(common):
        return lines
    lines += ['', '| robot | laser | beams | steps | float32-equal | within 5 cm '
              '| intensities equal | geometry | stale scans real / ours '
              '| worst beams (#beam step real/ours, m) |',
              '|---|---|---:|---|---:|---:|---:|---|---|---|']
    lines += scan_rows(a, b, ia, ib, worst)
    lines += ['', '| robot | odom max mm | odom yaw max mrad | gt max mm | gt yaw max mrad '
              '| odom twist max diff | stalls real | stalls ours | only real | only ours |',
              '|---|---:|---:|---:|---:|---:|---|---|---|---|']
    lines += pose_rows(a, b, ia, ib)
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('real', help='the capture of real Stage (.npz)')
    parser.add_argument('ours', help='the capture of ours (.npz)')
    parser.add_argument('--worst', type=int, default=WORST, help='beams listed per laser')
    args = parser.parse_args(argv)
    try:
        print('\n'.join(compare(args.real, args.ours, args.worst)))
    except (OSError, KeyError, ValueError) as err:
        sys.exit('compare.py: %s' % err)


if __name__ == '__main__':
    main()
