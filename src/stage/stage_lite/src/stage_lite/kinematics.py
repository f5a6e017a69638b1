"""Poses, Stage's velocity step and rectangle footprints (metres, radians, seconds).

Stage 4.3 moves a position model in velocity mode by `pose <- pose (+) (vx dt, vy dt, wz dt)`:
the translation is rotated by the OLD heading, then the yaw is added (explicit Euler in the
body frame, not an arc). Velocities are clamped to `velocity_bounds` first.
"""

import math

import numpy as np


def normalize(a):
    """Angle in [-pi, pi)."""
    return (a + math.pi) % (2 * math.pi) - math.pi


def compose(pose, delta):
    """pose (+) delta for (x, y, yaw) tuples: delta is expressed in pose's frame."""
    x, y, a = pose
    dx, dy, da = delta
    c, s = math.cos(a), math.sin(a)
    return (x + c * dx - s * dy, y + s * dx + c * dy, normalize(a + da))


def clamp_command(vx, vy, wz, bounds, drive):
    """The command after Stage's clamping; `bounds` = (xmin, xmax, ymin, ymax, amin, amax)
    in m/s and rad/s. A diff drive ignores vy. Raises ValueError on NaN or infinity."""
    for name, v in (('linear.x', vx), ('linear.y', vy), ('angular.z', wz)):
        if not math.isfinite(v):
            raise ValueError('%s must be finite, got %r' % (name, v))
    if drive == 'diff':
        vy = 0.0
    xmin, xmax, ymin, ymax, amin, amax = bounds
    return (min(max(vx, xmin), xmax), min(max(vy, ymin), ymax), min(max(wz, amin), amax))


def euler_step(pose, command, dt):
    """Stage's position update over dt seconds: body-frame translation, then the turn."""
    vx, vy, wz = command
    return compose(pose, (vx * dt, vy * dt, wz * dt))


def body_pose(pose, origin):
    """Centre and yaw of a body whose geometry is offset by `origin` (x, y, yaw) from `pose`."""
    return compose(pose, origin)


def rect_corners(cx, cy, yaw, sx, sy):
    """4x2 corners of an sx x sy rectangle centred on (cx, cy), counter-clockwise."""
    c, s = math.cos(yaw), math.sin(yaw)
    hx, hy = sx / 2.0, sy / 2.0
    local = np.array([(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)])
    return np.column_stack((cx + c * local[:, 0] - s * local[:, 1],
                            cy + s * local[:, 0] + c * local[:, 1]))


def rect_samples(cx, cy, yaw, sx, sy, spacing):
    """Points covering the rectangle, edges included, no two neighbours more than `spacing`
    apart: every grid cell of that size that the rectangle overlaps holds one when the
    rectangle is axis-aligned (and nearly every one otherwise)."""
    nx = max(2, math.ceil(sx / spacing - 1e-9) + 1)
    ny = max(2, math.ceil(sy / spacing - 1e-9) + 1)
    u = np.linspace(-sx / 2, sx / 2, nx)
    v = np.linspace(-sy / 2, sy / 2, ny)
    uu, vv = np.meshgrid(u, v)
    c, s = math.cos(yaw), math.sin(yaw)
    return cx + c * uu.ravel() - s * vv.ravel(), cy + s * uu.ravel() + c * vv.ravel()


def rect_gap(a, b):
    """Separating gap between two convex polygons (Nx2 corners) by the separating-axis test:
    > 0 the distance along the best axis, <= 0 they overlap."""
    best = -math.inf
    for poly in (a, b):
        n = len(poly)
        for i in range(n):
            ex, ey = poly[(i + 1) % n] - poly[i]
            length = math.hypot(ex, ey)
            if length == 0:
                continue
            ax, ay = -ey / length, ex / length
            pa = a[:, 0] * ax + a[:, 1] * ay
            pb = b[:, 0] * ax + b[:, 1] * ay
            gap = max(pb.min() - pa.max(), pa.min() - pb.max())
            best = max(best, gap)
    return best


def z_overlap(a, b):
    """True when the height ranges (z0, z1) overlap (touching does not count)."""
    return a[0] < b[1] and b[0] < a[1]
