"""Rays that look for models, as Stage 4.3's fiducial finder and blobfinder cast them (no rospy).

Stage's sensors all walk the grid with World::Raytrace (raytrace.py's walk, quirks included);
what differs between them is the rule that says whether a block in a cell stops the ray. The
ranger's rule (another robot tree, ranger_return >= 0, the beam's height in the block's range)
is raytrace.py's own. The fiducial finder's and the blobfinder's rule is simpler: a block stops
the ray when its model is NOT RELATED to the finder (Model::IsRelated: another tree of models;
ranger_return, obstacle_return and blob_return play no part), and
- with the z test (the fiducial finder): when the ray's height lies in the block's height
  range, ends included;
- without it (the blobfinder): at any height.
The first such block in the walk's order (cell by cell; in a cell, the first drawn) is the hit.

The rule is handed to raytrace.trace, unchanged, as arrays: a table of the first static model
per cell that passes the rule (built here per ray height and finder tree, and kept), every
model "visible" (no ranger_return test), and for the blobfinder block height ranges that
contain every height.

What Sight needs from the world: its models (their blocks and roots), its robots (every model
of a robot's tree moves: the others are static bodies) and its grid (world.space), all as
world_load made them; the layer a step's rays read is the caller's ((updates + 1) % 2 during
a step, as World::Raytrace reads it).
"""
import math

import numpy as np

from . import grid
from .jit import kernel
from .raytrace import trace

NO_Z = None      # the z of a ray cast without the z test


@kernel
def cast_fan(ox, oy, oz, angles, rng, finder_root, layer, ppm, rx0, ry0, nrx, nry, reg_count,
             reg_static, reg_dyn, st_first, dyn_head, ent_block, ent_next, ent_seq, blk_model,
             blk_zmin, blk_zmax, model_root, model_rr, out_range, out_model):
    """Rays from (ox, oy, oz) at each of `angles` (world frame, rad), `rng` m long, through
    raytrace.trace with st_first as its one static ray class: ranges and models hit (-1)."""
    for k in range(angles.shape[0]):
        r, m = trace(ox, oy, oz, angles[k], rng, ppm, 0, finder_root, layer, rx0, ry0, nrx, nry,
                     reg_count, reg_static, reg_dyn, st_first, dyn_head, ent_block, ent_next,
                     ent_seq, blk_model, blk_zmin, blk_zmax, model_root, model_rr)
        out_range[k] = r
        out_model[k] = m


def moving_models(robots):
    """The indices of every model a robot carries, at any depth, the robots included (the
    models world_load draws as moving bodies)."""
    out = set()
    todo = [r.model for r in robots]
    while todo:
        m = todo.pop()
        out.add(m.index)
        todo.extend(m.children)
    return out


class Sight:
    """Rays with the finders' rule through a loaded world's grid.

    models, robots, space: the world's (World.models, .robots, .space)."""

    def __init__(self, models, robots, space):
        self.space = space
        self.models = list(models)        # by index: what a ray's hit names
        self.model_root = np.array([m.root.index for m in models], np.int64)
        self.visible = np.zeros(len(models), np.float64)   # no ranger_return test
        moving = moving_models(robots)
        xs, ys, ms, zmin, zmax = [], [], [], [], []
        for m in models:
            if m.index in moving:
                continue
            for block in m.blocks:
                x, y = m.outline_cells(block, space.ppm)
                lo, hi = m.block_z(block)
                n = x.size
                xs.append(x)
                ys.append(y)
                ms.append(np.full(n, m.index, np.int64))
                zmin.append(np.full(n, lo))
                zmax.append(np.full(n, hi))
        if xs:
            x, y = np.concatenate(xs), np.concatenate(ys)
            reg = (((y >> grid.RBITS) - space.ry0) * space.nrx
                   + ((x >> grid.RBITS) - space.rx0))
            page = space.reg_static[reg].astype(np.int64)   # pages keep their numbers
            cell = (y & (grid.REGION - 1)) * grid.REGION + (x & (grid.REGION - 1))
            self._key = page * grid.REGION_CELLS + cell
            self._model = np.concatenate(ms)
            self._zmin, self._zmax = np.concatenate(zmin), np.concatenate(zmax)
        else:
            self._key = self._model = np.zeros(0, np.int64)
            self._zmin = self._zmax = np.zeros(0)
        self._pages = max(1, int(space.reg_static.max(initial=-1)) + 1)
        self._tables = {}
        # the trees the static drawings belong to: a finder of any other tree sees them all
        self._static_roots = set(self.model_root[self._model].tolist())
        self._any_z = (np.zeros(0), np.zeros(0))

    def tree_key(self, finder_root):
        """The tree static_first's tables know a finder's by: its own if it holds static
        bodies, else -1 (one table for all those)."""
        return finder_root if finder_root in self._static_roots else -1

    def static_first(self, z, finder_root):
        """(1, pages, cells) int32: per static cell, the first static model (load order:
        Stage's drawing order) a ray of height z (NO_Z: any height) from finder_root's tree
        stops at, or -1. Built once per z and tree (one for all the trees that hold no
        static drawing)."""
        key = (z, self.tree_key(finder_root))
        table = self._tables.get(key)
        if table is None:
            ok = self.model_root[self._model] != finder_root
            if z is not NO_Z:
                ok &= (z >= self._zmin) & (z <= self._zmax)
            keys, models = self._key[ok], self._model[ok]
            order = np.lexsort((models, keys))
            keys, models = keys[order], models[order]
            first = np.ones(keys.size, bool)
            first[1:] = keys[1:] != keys[:-1]
            table = np.full((1, self._pages, grid.REGION_CELLS), -1, np.int32)
            table.reshape(-1)[keys[first]] = models[first]
            self._tables[key] = table
        return table

    def _heights(self, ztest):
        sp = self.space
        if ztest:
            return sp.blk_zmin, sp.blk_zmax
        if self._any_z[0].size != sp.blk_zmin.size:
            n = sp.blk_zmin.size
            self._any_z = (np.full(n, -math.inf), np.full(n, math.inf))
        return self._any_z

    def cast(self, origin, angles, rng, finder, ztest, layer):
        """Rays from origin (x, y, z, _) in the world at each of `angles` (rad, world frame),
        rng m long, that stop at the first block of a model not related to `finder` (with
        ztest: whose height range holds z), through the grid's `layer`: (ranges m, model
        indices hit or -1), float64 and int64 arrays."""
        sp = self.space
        angles = np.ascontiguousarray(angles, np.float64)
        n = angles.shape[0]
        out_range = np.empty(n, np.float64)
        out_model = np.empty(n, np.int64)
        root = finder.root.index
        z = float(origin[2])
        zmin, zmax = self._heights(ztest)
        cast_fan(float(origin[0]), float(origin[1]), z, angles, float(rng), root, int(layer),
                 sp.ppm, sp.rx0, sp.ry0, sp.nrx, sp.nry, sp.reg_count, sp.reg_static,
                 sp.reg_dyn, self.static_first(z if ztest else NO_Z, root), sp.dyn_head,
                 sp.ent_block, sp.ent_next, sp.ent_seq, sp.blk_model, zmin, zmax,
                 self.model_root, self.visible, out_range, out_model)
        return out_range, out_model
