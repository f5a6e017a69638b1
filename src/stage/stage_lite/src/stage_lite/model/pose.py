"""Stage 4.3's pose arithmetic, operation for operation (libstage/stage.hh).

Stage's geometry is reproduced to the last bit only if every double is computed in Stage's
order: a body's cells come from floor(x * ppm) of vertices that went through these sums. So
these functions keep Stage's order of operations and its own angle normalisation.
"""
import math

#: Stage's unit_angle for degrees: M_PI / 180, one rounded constant multiplied in.
DEG = math.pi / 180.0


def stage_normalize(a):
    """Stage's normalize(): into [-pi, pi] by adding or subtracting 2 pi in a loop.

    Not wrap_angle's modulo: a value already within [-pi, pi] is returned unchanged, pi stays
    pi, and a value just outside gets exactly one 2 pi subtracted (bit-exact with Stage)."""
    while a < -math.pi:
        a += 2.0 * math.pi
    while a > math.pi:
        a -= 2.0 * math.pi
    return a


def pose_add(p, q):
    """Stage's Pose::operator+: q (x, y, z, a), expressed in p's frame, put in p's parent frame."""
    px, py, pz, pa = p
    qx, qy, qz, qa = q
    cosa = math.cos(pa)
    sina = math.sin(pa)
    return (px + qx * cosa - qy * sina, py + qx * sina + qy * cosa, pz + qz,
            stage_normalize(pa + qa))
