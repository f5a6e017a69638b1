"""Replay a capture of real Stage in stage_lite's model and compare what stageros published.

Golden data are made with stage_lite's test/golden/capture.py and make_golden.py (that
folder's README says how): per step, the velocity real Stage applied to each robot (its odom
twist), its ground-truth and odom poses, every scan. replay() loads the same world, replays
the velocities (for a `car` robot the command that gives them) and the reset_positions
call, and keeps what the model gave; the check_* functions compare, and raise
AssertionError naming the step, the robot and the ranger where they differ:

- poses and odometry equal to the last bit (yaw read back from a quaternion: YAW_TOL);
- stalls at the same steps;
- scans float32-equal, except scans Stage's ranger thread raced. In Stage the rangers run
  in a worker thread beside the moves: usually they start after them (what stage_lite
  does), but now and then one reads its robot's pose before the move, or, for a robot being
  stalled, the provisional pose the move tried, while the region counts its walk reads
  change as robots are drawn anew (a region whose only body is being drawn anew is
  walked cell by cell or jumped over, depending on the instant). A raced scan must equal,
  on at least RACE_BEAMS of its beams, the scan stage_lite gives from one of those poses
  (most raced scans equal one of them on every beam; a scan from a wrong pose or a wrong
  walk shares about a quarter of its beams), and at most RACE_SHARE of the scans taken
  while robots were moving (or being stalled) may be raced (2 to 6 % in the captures).
"""
import json
import math
import os

import numpy as np

from ..model.pose import pose_add, stage_normalize
from ..model.world import load_world

YAW_TOL = 1e-12          # rad: yaw read back from the published quaternion
RACE_BEAMS = 0.5         # share of a raced scan's beams equal to one of the race readings
RACE_SHARE = 0.1         # largest share of the scans taken while robots moved that may race


def load(path):
    """(arrays, meta) of a golden .npz."""
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files if k != 'meta'}
        return arrays, json.loads(str(data['meta']))


def world_path(gold, meta, worlds_dir, scratch_dir):
    """The captured world's file: the one embedded in the capture (make_golden.py --embed),
    written with its bitmaps into scratch_dir, else worlds_dir's."""
    if not meta.get('embedded'):
        return os.path.join(worlds_dir, meta['world'])
    for name in meta['embedded']:
        with open(os.path.join(scratch_dir, name), 'wb') as f:
            f.write(gold['file/' + name].tobytes())
    return os.path.join(scratch_dir, meta['world'])


def car_goal(robot, twist):
    """The (speed, steer) command whose `car` velocity is twist (vx, vy, wz)."""
    vx, _, wz = twist
    wb = robot.model.wheelbase
    sign = 1.0 if vx >= 0 else -1.0
    return (sign * math.hypot(vx, wz * wb), 0.0, 0.0, math.atan2(sign * wz * wb, sign * vx))


def race_poses(world, robot, before):
    """The poses a raced ranger may read: before the move, and the move's provisional one."""
    vx, vy, vz, va = robot.velocity
    if not (vx or vy or vz or va):
        return []
    dt = world.interval_sim_s
    return [before, pose_add(before, (vx * dt, vy * dt, vz * dt, stage_normalize(va * dt)))]


def replay(world_path, gold, meta):
    """Per step of the golden data, what stage_lite's model gives: a list of dicts with
    poses, odoms, stalled, moving (per robot), scans and intensities (per robot, per ranger)
    and races (per robot, per ranger: the race readings)."""
    world = load_world(world_path)
    frames = []
    for row, step in enumerate(gold['steps']):
        if step == meta.get('reset_before'):
            world.reset()
        before = []
        for r, robot in enumerate(world.robots):
            twist = gold['r%d_odom_twist' % r][row]
            robot.goal = (car_goal(robot, twist) if robot.drive == 'car'
                          else (twist[0], twist[1], 0.0, twist[2]))
            before.append(robot.model.pose)
        world.step()
        robots = world.robots
        frames.append(dict(
            poses=[r.pose for r in robots], odoms=[r.odom_pose for r in robots],
            stalled=[r.stalled for r in robots],
            # Move draws a robot anew whenever its velocity is not zero, stalled or not
            moving=[any(r.velocity) for r in robots],
            scans=[[v.ranges.copy() for v in r.rangers] for r in robots],
            intensities=[[v.intensities.copy() for v in r.rangers] for r in robots],
            races=[[[world.scan_from(v, p) for p in race_poses(world, r, before[i])]
                    for v in r.rangers] for i, r in enumerate(robots)]))
    return frames


def check_poses(gold, frames):
    for row, frame in enumerate(frames):
        for r, (pose, odom) in enumerate(zip(frame['poses'], frame['odoms'], strict=True)):
            for ours, key in ((pose, 'gt_pose'), (odom, 'odom_pose')):
                real = gold['r%d_%s' % (r, key)][row]
                where = 'step %d, robot %d, %s: ours %r, real %r' % (row + 1, r, key, ours,
                                                                     tuple(real))
                assert ours[:2] == tuple(real[:2]), where
                assert abs(ours[2] - real[2]) <= YAW_TOL, where


def stall_steps(arrays, robot):
    """The steps (of arrays['steps']) at which a capture's robot stalled: its odom twist (the
    velocity Stage applied) non-zero while its ground-truth pose equals the step before's
    (Stage keeps the stall flag of a robot that is not commanded to move)."""
    twist, pose = arrays['r%d_odom_twist' % robot], arrays['r%d_gt_pose' % robot]
    stalled = np.any(twist[1:] != 0, axis=1) & np.all(pose[1:] == pose[:-1], axis=1)
    return set(arrays['steps'][1:][stalled].tolist())


def check_stalls(gold, frames):
    steps = gold['steps']
    for r in range(len(frames[0]['poses'])):
        twist = gold['r%d_odom_twist' % r]
        real = sorted(stall_steps(gold, r))
        ours = [int(steps[row]) for row in range(1, len(frames))
                if twist[row].any() and frames[row]['stalled'][r]]
        assert real == ours, 'robot %d stalls: ours at steps %s, real at %s' % (r, ours, real)


def check_scans(gold, frames):
    """Returns (scans compared, scans raced)."""
    compared = raced = racing = 0
    for row, frame in enumerate(frames):
        for r, scans in enumerate(frame['scans']):
            for k, ours in enumerate(scans):
                real = gold['r%d_scan%d_ranges' % (r, k)][row]
                if np.isnan(real).all():    # Stage publishes no scan before the ranger's
                    continue                # first update
                compared += 1
                where = 'step %d, robot %d, ranger %d' % (row + 1, r, k)
                if not any(frame['moving']):
                    assert np.array_equal(real, ours), where + ': ranges differ'
                    assert np.array_equal(gold['r%d_scan%d_intensities' % (r, k)][row],
                                          frame['intensities'][r][k]), where + ': intensities'
                    continue
                racing += 1
                if np.array_equal(real, ours):
                    continue
                raced += 1
                share = max([float(np.mean(real == ours))]
                            + [float(np.mean(real == scan)) for scan in frame['races'][r][k]])
                assert share >= RACE_BEAMS, '%s: ranges differ (best reading %.0f %% equal)' \
                    % (where, 100 * share)
    assert raced <= RACE_SHARE * max(1, racing), '%d of %d scans raced' % (raced, racing)
    return compared, raced
