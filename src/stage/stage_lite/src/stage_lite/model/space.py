"""The grid's storage: static bodies put in once, moving bodies drawn and erased as they move.

Space owns the arrays grid.py's and raytrace.py's kernels walk (see grid.py for what they
mean) and keeps the region table large enough for every body, growing it when a robot drives
out of it.
"""
import math

import numpy as np

from . import grid, raytrace

REGION = grid.REGION
MARGIN_REGIONS = 4        # table margin around the bodies, regions (2.56 m at 2 cm cells)
#: From this many rays in a step, they are shared among numba's threads (below it, waking
#: the threads costs more than it saves). In one process, shared: cave's 1,600 sonar rays
#: 0.74 -> 0.57 ms, large.world's 1,800 laser rays 0.61 -> 0.40, 100 swarmbots' 1,200 IR
#: rays 0.41 -> 0.31; simple.world's 360 rays 0.13 -> 0.14.
PARALLEL_RAYS = 1000
PAGES_AT_START = 64       # moving bodies' pages (8 KB each) before the pool grows
# The pool grows by a quarter of itself, at least PAGES_GROWN_AT_LEAST pages: a spreading
# swarm takes pages step after step, and doubling left up to half of them unused (1,000
# swarmbots at 30 s: 1,200 pages in use of 2,048, 7 MB).
GROWTH_DIVISOR = 4
PAGES_GROWN_AT_LEAST = 64


class DynamicBlock:
    """A block of a moving model: its model, its height range in the world, its cell class."""

    def __init__(self, model, block, zmin, zmax):
        self.model = model
        self.block = block
        self.zmin = zmin
        self.zmax = zmax


def _capacity(block, ppm):
    """The most cells one drawing of the block's outline can take, at any pose."""
    pts = block.pts
    d = np.roll(pts, -1, axis=0) - pts
    return int(np.sum(np.ceil(np.hypot(d[:, 0], d[:, 1]) * ppm * math.sqrt(2.0)) + 2)) + 4


def _pages(block, ppm):
    """The most regions one drawing of the block can touch."""
    pts = block.pts
    c = pts.mean(axis=0)
    diameter = 2.0 * float(np.max(np.hypot(pts[:, 0] - c[0], pts[:, 1] - c[1]))) * ppm + 2
    return (int(math.ceil(diameter / REGION)) + 1) ** 2


class Space:
    """The grid: region table, static cells, moving bodies' cell lists, and the ray cast."""

    def __init__(self, ppm, n_models, model_root, model_rr, model_obstacle):
        self.ppm = ppm
        self.model_root = np.asarray(model_root, np.int64)
        self.model_rr = np.asarray(model_rr, np.float64)
        self.model_obstacle = np.asarray(model_obstacle, np.bool_)
        self.seq = n_models          # drawings after the load come after every load-time one
        self.rx0 = self.ry0 = 0
        self.nrx = self.nry = 0
        self.reg_count = np.zeros(0, np.int64)
        self.reg_static = np.zeros(0, np.int32)
        self.reg_dyn = np.zeros(0, np.int32)
        self.reg_dyncount = np.zeros(0, np.int64)

    # ---- load --------------------------------------------------------------------------
    def build(self, static_cells, ray_zs, dynamic_blocks, coll_ranges, extent):
        """static_cells: (x, y, model, zmin, zmax) arrays of every static drawing, in load
        order; ray_zs: the beam heights; dynamic_blocks: DynamicBlock list with .coll set to
        an index into coll_ranges (zmin, zmax pairs); extent: cell box (x0, y0, x1, y1) that
        the table must hold at first."""
        if len(coll_ranges) > 32:
            raise ValueError('more than 32 height ranges of moving bodies')
        self.ray_zs = list(ray_zs)
        self.coll_ranges = list(coll_ranges)
        self._put_static(static_cells, extent)
        self._build_dynamic(dynamic_blocks)

    def replace_static(self, static_cells):
        """The static drawings replaced by these (models made, moved or resized at run
        time, runtime_models.py); the moving bodies' drawings are kept."""
        np.subtract.at(self.reg_count, self._regions(*self._static_xy), 2)
        self.reg_static[:] = -1
        self._put_static(static_cells, None)

    def _put_static(self, static_cells, extent):
        """The static pages (per beam height the first model seen, per moving bodies'
        height range whether an obstacle is there) and the regions' counts of the static
        drawings; the table grown to hold them (and extent, if given)."""
        sx, sy, smodel, szmin, szmax = static_cells
        ray_zs, coll_ranges = self.ray_zs, self.coll_ranges
        if sx.size or extent is not None:
            x0, y0, x1, y1 = extent if extent is not None else (
                int(sx.min()), int(sy.min()), int(sx.max()), int(sy.max()))
            if sx.size:
                x0, y0 = min(x0, int(sx.min())), min(y0, int(sy.min()))
                x1, y1 = max(x1, int(sx.max())), max(y1, int(sy.max()))
            self.resize(x0, y0, x1, y1)
        self._static_xy = (sx, sy)
        # static pages: one per region holding static drawings
        reg = self._regions(sx, sy)
        regions, page_of = np.unique(reg, return_inverse=True)
        self.reg_static[regions] = np.arange(regions.size, dtype=np.int32)
        np.add.at(self.reg_count, reg, 2)          # drawn in both layers
        cell = (sy & (REGION - 1)) * REGION + (sx & (REGION - 1))
        key = page_of.astype(np.int64) * grid.REGION_CELLS + cell
        npages = max(1, regions.size)
        self.st_ray = np.full((max(1, len(ray_zs)), npages, grid.REGION_CELLS), -1, np.int16
                              if len(self.model_rr) < 32000 else np.int32)
        flat_ray = self.st_ray.reshape(self.st_ray.shape[0], -1)
        visible = self.model_rr[smodel] >= 0.0 if smodel.size else np.zeros(0, bool)
        for k, z in enumerate(ray_zs):
            hit = visible & (z >= szmin) & (z <= szmax)
            keys, models = key[hit], smodel[hit]
            # the first drawing in each cell (lowest model index: load order) is the one seen
            order = np.lexsort((models, keys))
            keys, models = keys[order], models[order]
            first = np.ones(keys.size, bool)
            first[1:] = keys[1:] != keys[:-1]
            flat_ray[k, keys[first]] = models[first]
        self.st_coll = np.zeros((npages, grid.REGION_CELLS), np.uint32)
        flat_coll = self.st_coll.ravel()
        solid = self.model_obstacle[smodel] if smodel.size else np.zeros(0, bool)
        for k, (zmin, zmax) in enumerate(coll_ranges):
            hit = solid & (szmin <= zmax) & (szmax >= zmin)
            np.bitwise_or.at(flat_coll, key[hit], np.uint32(1 << k))

    def _build_dynamic(self, blocks):
        n = len(blocks)
        caps = [_capacity(b.block, self.ppm) for b in blocks]
        self.blk_pts = (np.vstack([b.block.pts for b in blocks]) if n
                        else np.zeros((0, 2))).astype(np.float64)
        sizes = [len(b.block.pts) for b in blocks]
        self.blk_pts_off = np.concatenate(([0], np.cumsum(sizes))).astype(np.int64)
        self.blk_radius = np.array([float(np.hypot(*b.block.pts.T).max()) if len(b.block.pts)
                                    else 0.0 for b in blocks])
        self._vx = np.zeros(max(sizes, default=1), np.int64)
        self._vy = np.zeros(max(sizes, default=1), np.int64)
        self.blk_model = np.array([b.model.index for b in blocks], np.int64)
        self.blk_zmin = np.array([b.zmin for b in blocks], np.float64)
        self.blk_zmax = np.array([b.zmax for b in blocks], np.float64)
        self.blk_class = np.array([b.coll for b in blocks], np.int64)
        self.rc_start = np.concatenate(([0], np.cumsum(caps)[:-1])).astype(np.int64) \
            if n else np.zeros(0, np.int64)
        total = int(sum(caps)) + 1
        self.rc_len = np.zeros((2, max(n, 1)), np.int64)
        self.rc_x = np.zeros((2, total), np.int64)
        self.rc_y = np.zeros((2, total), np.int64)
        entries = 2 * total          # a block's own, per cell its drawing can take (grid.entry_of)
        self.ent_block = np.zeros(entries, np.int64)
        self.ent_seq = np.zeros(entries, np.int64)
        self.ent_next = np.full(entries, -1, np.int64)
        # per entry the one before it in its cell's list; a head's: the list's tail
        self.ent_prev = np.full(entries, -1, np.int64)
        # the most regions each block's drawing can take, in both layers: the pages a
        # block's redraw may need at most; the pool grows as they are needed, never ahead of
        # them, so that a swarm costs the regions it covers (8 KB each), not its worst case
        self.blk_pages = np.array([2 * _pages(b.block, self.ppm) for b in blocks], np.int64)
        self.dyn_head = np.zeros((0, 2, grid.REGION_CELLS), np.int32)
        self.page_free = np.zeros(0, np.int64)
        self.free_state = np.zeros(1, np.int64)
        self.grow_pages(min(int(self.blk_pages.sum()), PAGES_AT_START))

    def pages_short(self, blocks):
        """Whether redrawing these blocks could need more free pages than the pool has."""
        return int(self.blk_pages[blocks].sum()) > int(self.free_state[0])

    def grow_pages(self, wanted=0):
        """Adds free pages to the pool: at least `wanted`, and a pool that has pages grows by
        a quarter of them at least (at least PAGES_GROWN_AT_LEAST); an empty pool takes
        `wanted` (the world's worst case, or PAGES_AT_START), one page at least."""
        have = self.dyn_head.shape[0]
        if have:
            added = max(wanted, have // GROWTH_DIVISOR, PAGES_GROWN_AT_LEAST)
        else:
            added = max(wanted, 1)
        shape = (have + added, 2, grid.REGION_CELLS)
        try:
            # In place where it can (realloc: a large block is remapped, not copied, so the
            # old and the new pool are never both in memory); refcheck refuses while any
            # other reference to the pool lives, and then it is copied.
            self.dyn_head.resize(shape, refcheck=True)
            self.dyn_head[have:] = -1
        except ValueError:
            head = np.full(shape, -1, np.int32)
            head[:have] = self.dyn_head
            self.dyn_head = head
        free = int(self.free_state[0])
        pool = np.empty(have + added, np.int64)
        pool[:free] = self.page_free[:free]
        pool[free:free + added] = np.arange(have + added - 1, have - 1, -1)
        self.page_free = pool
        self.free_state[0] = free + added

    def _hold_pages(self, blocks):
        while self.pages_short(blocks):
            self.grow_pages()

    # ---- the region table ----------------------------------------------------------------
    def _regions(self, x, y):
        return ((y >> grid.RBITS) - self.ry0) * self.nrx + ((x >> grid.RBITS) - self.rx0)

    def resize(self, x0, y0, x1, y1):
        """Makes the table hold cells x0..x1, y0..y1 (plus a margin), keeping its content."""
        rx0 = (x0 >> grid.RBITS) - MARGIN_REGIONS
        ry0 = (y0 >> grid.RBITS) - MARGIN_REGIONS
        rx1 = (x1 >> grid.RBITS) + MARGIN_REGIONS
        ry1 = (y1 >> grid.RBITS) + MARGIN_REGIONS
        if self.nrx:
            rx0, ry0 = min(rx0, self.rx0), min(ry0, self.ry0)
            rx1, ry1 = max(rx1, self.rx0 + self.nrx - 1), max(ry1, self.ry0 + self.nry - 1)
        nrx, nry = rx1 - rx0 + 1, ry1 - ry0 + 1
        new = {}
        for name, fill, dtype in (('reg_count', 0, np.int64), ('reg_static', -1, np.int32),
                                  ('reg_dyn', -1, np.int32), ('reg_dyncount', 0, np.int64)):
            table = np.full((nry, nrx), fill, dtype)
            if self.nrx:
                oy, ox = self.ry0 - ry0, self.rx0 - rx0
                table[oy:oy + self.nry, ox:ox + self.nrx] = getattr(self, name).reshape(
                    self.nry, self.nrx)
            new[name] = table.ravel()
        self.rx0, self.ry0, self.nrx, self.nry = rx0, ry0, nrx, nry
        for name, table in new.items():
            setattr(self, name, table)

    def hold(self, blocks, poses):
        """Grows the table if the blocks at these body poses (rows x, y, cos, sin) could
        reach out of it."""
        r = self.blk_radius[blocks] * self.ppm + 2
        xs = poses[:, 0] * self.ppm
        ys = poses[:, 1] * self.ppm
        x0, x1 = int(np.floor((xs - r).min())), int(np.ceil((xs + r).max()))
        y0, y1 = int(np.floor((ys - r).min())), int(np.ceil((ys + r).max()))
        if ((x0 >> grid.RBITS) < self.rx0 or (y0 >> grid.RBITS) < self.ry0
                or (x1 >> grid.RBITS) >= self.rx0 + self.nrx
                or (y1 >> grid.RBITS) >= self.ry0 + self.nry):
            self.resize(x0, y0, x1, y1)

    def draw(self, blocks, poses, layer, seqs):
        """Stage's UnMap then Map of blocks (int array) at their body poses (rows x, y, cos,
        sin) in `layer`, each with its drawing's sequence number."""
        self.hold(blocks, poses)
        start = 0
        while start < len(blocks):
            # as many blocks as the free pages surely hold, else more pages
            need = np.cumsum(self.blk_pages[blocks[start:]])
            end = start + int(np.searchsorted(need, self.free_state[0], side='right'))
            if end == start:
                self.grow_pages()
                continue
            grid.redraw(blocks[start:end], poses[start:end], seqs[start:end], layer, self.ppm,
                        self.blk_pts, self.blk_pts_off, self._vx, self._vy, self.rc_start,
                        self.rc_len, self.rc_x, self.rc_y, self.rx0, self.ry0, self.nrx,
                        self.nry, self.reg_count, self.reg_dyn, self.reg_dyncount,
                        self.dyn_head, self.ent_block, self.ent_next, self.ent_prev, self.ent_seq,
                        self.free_state, self.page_free, False,
                        self.reg_static, self.st_coll, self.blk_class, self.blk_model,
                        self.blk_zmin, self.blk_zmax, self.model_root, self.model_obstacle)
            start = end

    def move(self, blocks, new_poses, old_poses, seqs, layer):
        """ModelPosition::Move's grid work (grid.move): the blocks drawn at the new poses,
        tested, drawn back at the old ones on a collision; seqs: (2, blocks) drawing numbers.
        Returns grid.NO_HIT or what was hit."""
        self.hold(blocks, new_poses)
        self._hold_pages(blocks)
        return grid.move(blocks, new_poses, old_poses, seqs, layer, self.ppm, self.blk_pts,
                         self.blk_pts_off, self._vx, self._vy, self.rc_start, self.rc_len,
                         self.rc_x, self.rc_y, self.rx0, self.ry0, self.nrx, self.nry,
                         self.reg_count, self.reg_static, self.reg_dyn, self.reg_dyncount,
                         self.st_coll, self.blk_class, self.dyn_head, self.ent_block,
                         self.ent_next, self.ent_prev, self.ent_seq, self.free_state,
                         self.page_free, self.blk_model, self.blk_zmin, self.blk_zmax,
                         self.model_root, self.model_obstacle)

    def collides(self, blocks, layer):
        """Block::TestCollision of the blocks as drawn in `layer` (grid.collides)."""
        return grid.collides(blocks, layer, self.rc_start, self.rc_len, self.rc_x, self.rc_y,
                             self.rx0, self.ry0, self.nrx, self.nry, self.reg_static,
                             self.reg_dyn, self.st_coll, self.blk_class, self.dyn_head,
                             self.ent_block, self.ent_next, self.blk_model, self.blk_zmin,
                             self.blk_zmax, self.model_root, self.model_obstacle)

    def next_seq(self):
        self.seq += 1
        return self.seq

    # ---- rays ------------------------------------------------------------------------------
    def cast(self, origins, incr, offsets, sensor, rmax, ray_class, root, layer):
        """The rays of sensors (per sensor: its first ray's pose x, y, z, angle, its angle
        increment, its range, its beam height's class and its robot's root model; offsets
        of each sensor's rays; sensor[k]: the sensor of ray k): (ranges m, models hit or -1).
        Many rays are shared among numba's threads, a few are cast in this one."""
        args = self.cast_args(origins, incr, offsets, sensor, rmax, ray_class, root, layer)
        run_cast(args)
        return args[-2], args[-1]

    def cast_args(self, origins, incr, offsets, sensor, rmax, ray_class, root, layer):
        """cast()'s rays as raytrace.cast_scans takes them, the ranges and the models hit to
        be written into its last two arrays (for a kernel that casts them beside other
        work)."""
        n = sensor.shape[0]
        return (origins, incr, offsets, sensor, rmax, ray_class, root, layer, self.ppm,
                self.rx0, self.ry0, self.nrx, self.nry, self.reg_count, self.reg_static,
                self.reg_dyn, self.st_ray, self.dyn_head, self.ent_block, self.ent_next,
                self.ent_seq, self.blk_model, self.blk_zmin, self.blk_zmax, self.model_root,
                self.model_rr, np.empty(n, np.float64), np.empty(n, np.float64),
                np.empty(n, np.int64))


def run_cast(args):
    """raytrace.cast_scans of Space.cast_args's args; from PARALLEL_RAYS rays on, shared among
    numba's threads."""
    parallel = args[3].shape[0] >= PARALLEL_RAYS
    (raytrace.cast_scans_parallel if parallel else raytrace.cast_scans)(*args)
