"""A step's rays and fiducial finders on numba's threads, in one parallel region (no rospy).

numba's threads sleep between parallel kernels (jit.py: OMP_WAIT_POLICY=PASSIVE), and waking
them costs tens of microseconds a call. A step's rangers (casts.py) and finders (finders.py)
read the same grid layer and poses and each writes only its own outputs, so one region does
both: thread t casts every parts-th ray and updates every parts-th finder from the t-th on.
The readings are those of casting and updating them apart, to the bit. It is also the
finders' only parallel kernel (with no rays): numba 0.61 (Debian 13's) takes some 40 s to
compile each kernel of that size.
"""
import numpy as np

from .finders import prepare_ids, see_one
from .jit import njit, numba_threads, prange
from .raytrace import cast_ray, scan_angles
from .space import run_cast

#: From this many finder-candidate pairs in a step, the finders are shared among numba's
#: threads (each pair may cost a ray).
PARALLEL_CANDIDATES = 1000
#: Rays and finders together from this much work: rays, plus finder-candidate pairs over
#: PAIRS_PER_RAY (a pair costs a few tests, now and then a ray). SFU's 752 sonar rays and 94
#: finders of 94 robots: 0.31 ms apart, 0.24 together (this machine, one process).
TOGETHER_WORK = 500
PAIRS_PER_RAY = 16
_NO_RAYS = (np.zeros((0, 4)), np.zeros(0), np.zeros(1, np.int64), np.zeros(0, np.int64),
            np.zeros(0), np.zeros(0, np.int64), np.zeros(0, np.int64))


def update_all(finders, index, sight, layer):
    """ModelFiducial::Update of each finder in turn, as Fiducial.update_one_by_one does it,
    in one kernel (finders.prepare_ids)."""
    ids = np.fromiter((f.index for f in finders), np.int64, len(finders))
    finding = prepare_ids(ids, {f.index: f for f in finders}.__getitem__, index, sight, layer)
    sense(None, finding)
    finding.publish()


def sense(casting, finding):
    """The kernels of a step's casting (casts.Casting) and finding (finders.Finding), either
    None: on numba's threads, together in one region, when the finders are many or both
    together are worth it; else each in this thread (the rays on the threads from
    space.PARALLEL_RAYS)."""
    if finding is not None and finding.args is None:
        finding = None
    rays = 0 if casting is None else casting.rays()
    pairs = 0 if finding is None else finding.pairs()
    if finding is not None and numba_threads() > 1 and (
            pairs >= PARALLEL_CANDIDATES
            or (rays and rays + pairs // PAIRS_PER_RAY >= TOGETHER_WORK)):
        cast = (casting.args if casting is not None
                else finding.space.cast_args(*_NO_RAYS, finding.layer))
        _cast_and_find(numba_threads(), *cast, *finding.args)
        return
    if casting is not None:
        run_cast(casting.args)
    if finding is not None:
        finding.run()


@njit(parallel=True, cache=True)
def _cast_and_find(parts, origins, incr, offsets, sensor, rmax, ray_class, root, layer, ppm,
                   rx0, ry0, nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head,
                   ent_block, ent_next, ent_seq, blk_model, blk_zmin, blk_zmax, model_root,
                   model_rr, angles, out_range, out_model, fin, ints, classes, poses, order_x,
                   order_y, by_rank, rank_at, key, f_root, index, ret, f_layer, f_ppm, f_rx0,
                   f_ry0, f_nrx, f_nry, f_reg_count, f_reg_static, f_reg_dyn, st_first,
                   f_dyn_head, f_ent_block, f_ent_next, f_ent_seq, f_blk_model, f_blk_zmin,
                   f_blk_zmax, f_model_root, visible, count, nearest, out_c, out_f, out_id):
    """raytrace.cast_scans's arguments, then finders.see_one's (the row and xs, ys aside):
    both, the work dealt out in turn to `parts` threads (neighbouring finders, whose work
    is alike, to different threads)."""
    scan_angles(origins, incr, offsets, angles)
    xs = poses[:, 0].copy()
    ys = poses[:, 1].copy()
    rays = sensor.shape[0]
    finders = fin.shape[0]
    for t in prange(parts):
        for k in range(t, rays, parts):
            cast_ray(k, sensor, origins, angles, rmax, ray_class, root, layer, ppm, rx0, ry0,
                     nrx, nry, reg_count, reg_static, reg_dyn, st_ray, dyn_head, ent_block,
                     ent_next, ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr,
                     out_range, out_model)
        for i in range(t, finders, parts):
            see_one(i, fin, ints, classes, poses, xs, ys, order_x, order_y, by_rank, rank_at,
                    key, f_root, index, ret, f_layer, f_ppm, f_rx0, f_ry0, f_nrx, f_nry,
                    f_reg_count, f_reg_static, f_reg_dyn, st_first, f_dyn_head, f_ent_block,
                    f_ent_next, f_ent_seq, f_blk_model, f_blk_zmin, f_blk_zmax, f_model_root,
                    visible, count, nearest, out_c, out_f, out_id)
