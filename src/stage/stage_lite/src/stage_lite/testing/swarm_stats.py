"""Swarm statistics of a run of robots' poses, to compare simulators by what a swarm does.

Poses come as an array (T, N, 3) of x, y (m) and heading a (rad, counter-clockwise from +x)
for T states at the sim times t_s (T,) (s, increasing, first state at the start of the run)
and N robots. The statistics are taken at chosen times; each uses the states up to then:

- path length (m): per robot, the sum of its straight steps in x, y so far;
- moving share: the share of robots whose path over the last `window_s` exceeds
  `moved_m` (a robot in its first `window_s` counts its path since the start);
- mean speed (m/s): the mean path over the last `window_s`, divided by the window;
- alignment: the length of the mean heading unit vector, 1 when all face one way, near 0
  when headings are spread evenly;
- nearest-neighbour spacing (m): the mean distance of each robot to its nearest other robot;
- distance to places (m): the mean distance of each robot to the nearest of given points
  (a foraging world's sources or sinks).

Pure numpy, no rospy; bad input raises ValueError.
"""
import numpy as np

WINDOW_S = 1.0    # s: the "last second" of the moving share and the mean speed
MOVED_M = 0.01    # m: a robot that went further than this in the window moved
RANGE_TOL = 1e-6  # a statistic this close to the runs' min or max is within them (float32)


def _check_poses(t_s, pose):
    t_s = np.asarray(t_s, dtype=np.float64)
    pose = np.asarray(pose, dtype=np.float64)
    if pose.ndim != 3 or pose.shape[2] != 3:
        raise ValueError('pose must be (T, N, 3), got shape %r' % (pose.shape,))
    if t_s.shape != (pose.shape[0],):
        raise ValueError('t_s must be (T,) = (%d,), got shape %r' % (pose.shape[0], t_s.shape))
    if pose.shape[0] == 0:
        raise ValueError('no states')
    if not (np.all(np.isfinite(t_s)) and np.all(np.isfinite(pose))):
        raise ValueError('t_s and pose must be finite')
    if np.any(np.diff(t_s) <= 0):
        raise ValueError('t_s must increase')
    return t_s, pose


def path_length(pose):
    """(T, N) path length of each robot up to each state (m); 0 at the first state."""
    pose = np.asarray(pose, dtype=np.float64)
    if pose.ndim != 3 or pose.shape[2] < 2:
        raise ValueError('pose must be (T, N, 3), got shape %r' % (pose.shape,))
    step = np.hypot(np.diff(pose[:, :, 0], axis=0), np.diff(pose[:, :, 1], axis=0))
    out = np.zeros(pose.shape[:2])
    np.cumsum(step, axis=0, out=out[1:])
    return out


def alignment(a):
    """Length of the mean heading unit vector of headings a (rad) over the last axis."""
    a = np.asarray(a, dtype=np.float64)
    if a.shape[-1] == 0:
        raise ValueError('no headings')
    return np.hypot(np.cos(a).mean(axis=-1), np.sin(a).mean(axis=-1))


def nearest_neighbour(xy):
    """Mean distance (m) of each of N >= 2 points xy (N, 2) to its nearest other point."""
    xy = np.asarray(xy, dtype=np.float64)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 2:
        raise ValueError('xy must be (N >= 2, 2), got shape %r' % (xy.shape,))
    d = np.hypot(xy[:, None, 0] - xy[None, :, 0], xy[:, None, 1] - xy[None, :, 1])
    np.fill_diagonal(d, np.inf)
    return float(d.min(axis=1).mean())


def nearest_place(xy, places):
    """Mean distance (m) of points xy (N, 2) to the nearest of places (P >= 1, 2)."""
    xy = np.asarray(xy, dtype=np.float64)
    places = np.asarray(places, dtype=np.float64)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] == 0:
        raise ValueError('xy must be (N >= 1, 2), got shape %r' % (xy.shape,))
    if places.ndim != 2 or places.shape[1] != 2 or places.shape[0] == 0:
        raise ValueError('places must be (P >= 1, 2), got shape %r' % (places.shape,))
    d = np.hypot(xy[:, None, 0] - places[None, :, 0], xy[:, None, 1] - places[None, :, 1])
    return float(d.min(axis=1).mean())


def state_index(t_s, times):
    """Index of the state at each of times (s); ValueError for a time no state is within
    a quarter of a step of."""
    t_s = np.asarray(t_s, dtype=np.float64)
    times = np.atleast_1d(np.asarray(times, dtype=np.float64))
    step = np.min(np.diff(t_s)) if len(t_s) > 1 else 1.0
    idx = np.clip(np.searchsorted(t_s, times), 0, len(t_s) - 1)
    lower = np.clip(idx - 1, 0, len(t_s) - 1)
    idx = np.where(np.abs(t_s[lower] - times) < np.abs(t_s[idx] - times), lower, idx)
    bad = np.abs(t_s[idx] - times) > step / 4
    if np.any(bad):
        raise ValueError('no state at t = %r s (states from %g to %g s)'
                         % (times[bad].tolist(), t_s[0], t_s[-1]))
    return idx


def swarm_stats(t_s, pose, times, flocking=False, places=None, window_s=WINDOW_S,
                moved_m=MOVED_M):
    """Statistics (a dict of arrays, one value per time) of a run at the given times (s).

    Always: 't_s', 'path_m' (mean path length per robot), 'moving_share', 'speed_mps'.
    With flocking: 'alignment', 'spacing_m' (mean nearest-neighbour spacing; N >= 2).
    With places, a dict name -> (P, 2) points: 'dist_<name>_m' for each.
    """
    t_s, pose = _check_poses(t_s, pose)
    if not (np.isfinite(window_s) and window_s > 0):
        raise ValueError('window_s must be > 0, got %r' % (window_s,))
    if not (np.isfinite(moved_m) and moved_m >= 0):
        raise ValueError('moved_m must be >= 0, got %r' % (moved_m,))
    if pose.shape[1] == 0:
        raise ValueError('no robots')
    idx = state_index(t_s, times)
    back = state_index(t_s, np.maximum(t_s[idx] - window_s, t_s[0]))
    path = path_length(pose)
    recent = path[idx] - path[back]
    out = {
        't_s': t_s[idx],
        'path_m': path[idx].mean(axis=1),
        'moving_share': (recent > moved_m).mean(axis=1),
        'speed_mps': recent.mean(axis=1) / window_s,
    }
    if flocking:
        out['alignment'] = alignment(pose[idx, :, 2])
        out['spacing_m'] = np.array([nearest_neighbour(pose[i, :, :2]) for i in idx])
    for name, points in (places or {}).items():
        out['dist_%s_m' % name] = np.array([nearest_place(pose[i, :, :2], points)
                                            for i in idx])
    return out


def parting_step(runs, tol_m=0.01):
    """First state index at which two of the runs (each poses (T, N, 3)) put one robot
    more than tol_m (m) apart in x, y, over the states they share; None if they never do."""
    if len(runs) < 2:
        raise ValueError('need at least two runs, got %d' % len(runs))
    if not (np.isfinite(tol_m) and tol_m >= 0):
        raise ValueError('tol_m must be >= 0, got %r' % (tol_m,))
    n = min(len(r) for r in runs)
    xy = [np.asarray(r, dtype=np.float64)[:n, :, :2] for r in runs]
    if len({r.shape for r in xy}) != 1:
        raise ValueError('runs must have the same robots, got shapes %r' % [r.shape for r in xy])
    apart = np.zeros(n)
    for i in range(len(xy)):
        for j in range(i + 1, len(xy)):
            d = np.hypot(xy[i][..., 0] - xy[j][..., 0], xy[i][..., 1] - xy[j][..., 1])
            apart = np.maximum(apart, d.max(axis=1))
    over = np.nonzero(apart > tol_m)[0]
    return int(over[0]) if len(over) else None


def within_runs(values, runs, tol=RANGE_TOL):
    """Per time, whether a statistic's values (T,) lie within the min..max of several runs'
    values at that time (runs: (R, T)), tol either side."""
    runs = np.asarray(runs, dtype=np.float64)
    values = np.asarray(values, dtype=np.float64)
    if runs.ndim != 2 or values.shape != runs.shape[1:]:
        raise ValueError('values (T,) and runs (R, T) expected, got %r and %r'
                         % (values.shape, runs.shape))
    return (values >= runs.min(axis=0) - tol) & (values <= runs.max(axis=0) + tol)


def runs_within_the_others(runs, tol=RANGE_TOL):
    """Per run of several (runs: (R, T), R >= 2), at how many times its statistic lies
    within the other runs' min..max: how well a run of the real program fits its own
    spread, the yardstick for a simulator held to the same runs."""
    runs = np.asarray(runs, dtype=np.float64)
    if runs.ndim != 2 or runs.shape[0] < 2:
        raise ValueError('at least two runs (R, T) expected, got %r' % (runs.shape,))
    return np.array([int(within_runs(runs[r], np.delete(runs, r, axis=0), tol).sum())
                     for r in range(runs.shape[0])])
