"""Loading a world as Stage 4.3 does: World::Load, then its post-load hook (no rospy).

World::Load reads the top-level properties, then turns every entity, in file order, into a
model (a `block( )` joins its model's body, a `sensor( )` its ranger, `window( )` is the
GUI's). World::LoadWorldPostHook then sizes every body (CalcSize) and maps it into the grid:
- the robots are the position models, in file order, each with the rangers it carries; they
  and every model they carry, at any depth, move;
- the static bodies' outlines are drawn into the grid once (MapPoly of every block);
- the moving bodies' blocks are registered with the grid (their height ranges, the region
  table's extent), and each robot is drawn at its start in both layers, its models in
  file order (each drawing numbered by its model's index, before any drawing of a step).
load() returns what the World runs on.
"""
import os
from dataclasses import dataclass

import numpy as np

from . import grid
from .blobfinder import Blobfinder
from .bodies import calc_size
from .camera import Camera
from .fiducial import Fiducial
from .models import Blinkenlight, Model
from .position import Position
from .ranger import Ranger
from .robot import RangerView, Robot, body_row
from .space import DynamicBlock, Space
from .worldfile import WorldError, Worldfile

#: Top-level properties Stage reads (the GUI ones too: the window is optional here).
TOP_LEVEL = ('name', 'show_clock', 'show_clock_interval', 'threads', 'paused',
             'confirm_on_quit', 'log')
#: Stage's model typetable: every type a world may name.
BUILTIN_TYPES = ('model', 'actuator', 'blinkenlight', 'blobfinder', 'bumper', 'camera',
                 'fiducial', 'gripper', 'lightindicator', 'position', 'ranger')
#: The class each type loads as (any other: a plain Model).
CLASSES = {'position': Position, 'ranger': Ranger, 'fiducial': Fiducial,
           'blobfinder': Blobfinder, 'camera': Camera, 'blinkenlight': Blinkenlight}
#: The types simulated here; the others are loaded as bodies only (with a WARN).
SIMULATED_TYPES = ('model', 'position', 'ranger', 'camera', 'fiducial', 'blobfinder')


@dataclass
class LoadedWorld:
    """What a World runs on."""

    resolution_m: float
    ppm: float               # cells per metre: 1 / resolution_m
    interval_us: int
    quit_time_s: float
    speedup: float
    window: dict | None      # the window( ) block's properties (numbers or strings), or None
    models: list             # every model, in file order
    robots: list             # a Robot per position model, in file order
    space: Space             # the grid, every body drawn
    ray_zs: list             # the rangers' beam heights, sorted: the grid's ray classes
    statics: list            # the models that never move
    static_cells: tuple      # their outline cells: (x, y) int32 arrays
    warnings: list           # loading's warnings, then Stage's "defined but not used"
    stageros_warnings: list  # what stageros cannot publish (rangers without or with several
                             # sensors); Stage's own program has nothing to say of them
    threads: int = 1         # Stage's worker threads (at least 1): its event queues 1..threads
    paused: bool = False     # `stage` does not start a paused world
    show_clock: bool = False  # `stage` prints its clock line every show_clock_interval steps
    show_clock_interval: int = 100


def load(path, rand48):
    """The world file at path, loaded (WorldError for what Stage refuses); rand48
    (glibc_random.Rand48, the world's drand48 stream) draws what Stage draws from drand48()
    while loading: the position models' odometry errors as their constructors draw them,
    `color "random"` as Model::Load does."""
    wf = Worldfile(path)
    resolution_m = wf.read_float(0, 'resolution', 0.02)
    if not resolution_m > 0:
        raise _top_error(wf, 'resolution', 'resolution must be > 0 m')
    interval_us = int(1e3 * wf.read_float(0, 'interval_sim', 100.0))
    if interval_us <= 0:
        raise _top_error(wf, 'interval_sim', 'interval_sim must be at least 0.001 ms')
    quit_time_s = int(1e6 * wf.read_float(0, 'quit_time', 0.0)) / 1e6
    speedup = wf.read_float(0, 'speedup', 1.0)
    threads = wf.read_int(0, 'threads', 1)
    if threads < 1:
        wf.warn(wf.prop(0, 'threads'), 'threads set to <1. Forcing to 1 (as Stage)')
        threads = 1
    flags = dict(paused=bool(wf.read_int(0, 'paused', 0)),
                 show_clock=bool(wf.read_int(0, 'show_clock', 0)),
                 show_clock_interval=max(1, wf.read_int(0, 'show_clock_interval', 100)))
    for name in TOP_LEVEL:
        if wf.exists(0, name):
            wf.read_string(0, name, '')
    window, models = _load_models(wf, path, rand48)
    ppm = 1.0 / resolution_m
    stageros_warnings = []
    robots, space, ray_zs, statics, static_cells = _post_load(models, ppm, stageros_warnings,
                                                              path)
    return LoadedWorld(resolution_m, ppm, interval_us, quit_time_s, speedup, window, models,
                       robots, space, ray_zs, statics, static_cells,
                       wf.warnings + wf.unused_warnings() + _overlaps(path, models, robots, space),
                       stageros_warnings, threads, **flags)


def _load_models(wf, path, rand48):
    """World::Load's models: (the window block's properties or None, every model)."""
    world_dir = os.path.dirname(os.path.abspath(path))
    window = None
    models = []
    by_entity = {}
    counts = {'model': 1}   # Stage's own ground model is model:0: a world's first is model:1
    for ent in wf.entities[1:]:
        parent = by_entity.get(ent.parent)
        if ent.kind == 'window':
            window = _read_window(wf, ent.index)
        elif ent.kind == 'block':
            if parent is None:
                raise WorldError(ent.path, ent.line, 'block( ) belongs inside a model')
            parent.load_block(wf, ent.index)
        elif ent.kind == 'sensor':
            if not isinstance(parent, Ranger):
                raise WorldError(ent.path, ent.line, 'sensor( ) belongs inside a ranger')
            parent.load_sensor(wf, ent.index)
        elif ent.kind in BUILTIN_TYPES:
            if ent.parent != 0 and parent is None:
                raise WorldError(ent.path, ent.line, 'a %s inside a window( )' % ent.kind)
            m = CLASSES.get(ent.kind, Model)(world_dir, parent, ent.kind, len(models),
                                             ent.index, counts)
            if isinstance(m, Position):
                m.draw_integration_error(rand48)
            m.load(wf, rand48)
            if ent.kind not in SIMULATED_TYPES:
                wf.warnings.append('%s:%d: %s models are not simulated here; loaded as a'
                                   ' body' % (ent.path, ent.line, ent.kind))
            models.append(m)
            by_entity[ent.index] = m
        else:
            raise WorldError(ent.path, ent.line, 'unknown model type "%s" (Stage: "Model'
                             ' type %s not found in model typetable")' % (ent.kind, ent.kind))
    return window, models


def _read_window(wf, e):
    """The GUI's window( ) properties, read as numbers or strings."""
    out = {}
    for name in wf.entities[e].props:
        vals = wf.read_values(e, name)
        nums = []
        for v in vals:
            try:
                nums.append(float(v))
            except ValueError:
                nums = None
                break
        vals = nums if nums is not None else vals
        out[name] = vals[0] if len(vals) == 1 else vals
    return out


def _post_load(models, ppm, warnings, path):
    """World::LoadWorldPostHook: every body sized, the robots found, every body drawn.
    Returns (robots, the grid, its ray heights, the static models, their outline cells)."""
    for m in models:
        calc_size(m.blocks, m.geom_size)
    robots, moving = _find_robots(models, warnings, path)
    space = Space(ppm, len(models), [m.root.index for m in models],
                  [m.ranger_return for m in models], [m.obstacle_return for m in models])
    cells = _static_cells(models, moving, ppm)
    dynamic, coll = _moving_blocks(models, moving, ppm)
    ray_zs = sorted({o[2] for r in robots for g in r.ranger_models for o in g.ray_origins()})
    space.build(cells, ray_zs, dynamic, coll, _extent(dynamic))
    _assign_blocks(robots, dynamic)
    _draw_at_start(space, robots)
    statics = [m for m in models if m.index not in moving]
    return robots, space, ray_zs, statics, (cells[0].astype(np.int32), cells[1].astype(np.int32))


def _find_robots(models, warnings, path):
    """(a Robot per position model in file order, the indices of every model that moves: the
    robots and what they carry). A ranger without a sensor is not published (a WARN)."""
    moving = set()
    robots = []
    for m in models:
        if isinstance(m, Position):
            moving.add(m.index)
            rangers = []
            for c in m.children:
                if isinstance(c, Ranger):
                    if not c.sensors:
                        warnings.append('%s: ranger %s has no sensor( ): not published'
                                        % (path, c.token))
                        continue
                    if len(c.sensors) > 1:
                        warnings.append('%s: ranger %s has %d sensors; stageros publishes the'
                                        ' first only' % (path, c.token, len(c.sensors)))
                    rangers.append(RangerView(c, c.sensors[0], m.geom_size[2]))
            robot = Robot(len(robots), m, rangers)
            robot.ranger_models = [v.model for v in rangers]
            robots.append(robot)
        elif m.parent is not None and m.parent.index in moving:
            moving.add(m.index)
    return robots, moving


def _static_cells(models, moving, ppm):
    """(x, y, model, zmin, zmax) arrays: every outline cell of the bodies that never move, in
    load order (MapPoly of each block)."""
    statics = ([], [], [], [], [])
    for m in models:
        if m.index in moving:
            continue
        for block in m.blocks:
            xs, ys = m.outline_cells(block, ppm)
            zmin, zmax = m.block_z(block)
            n = xs.size
            statics[0].append(xs)
            statics[1].append(ys)
            statics[2].append(np.full(n, m.index, np.int64))
            statics[3].append(np.full(n, zmin))
            statics[4].append(np.full(n, zmax))
    return tuple(np.concatenate(a) if a else np.zeros(0, t)
                 for a, t in zip(statics, (np.int64, np.int64, np.int64, float, float),
                                 strict=True))


def _moving_blocks(models, moving, ppm):
    """(a DynamicBlock per block of the moving models, in load order, the height ranges they
    are in: each block's .coll indexes it), each with its pixel vertices at its start."""
    dynamic = []
    coll = []
    for m in models:
        if m.index not in moving:
            continue
        for block in m.blocks:
            zmin, zmax = m.block_z(block)
            d = DynamicBlock(m, block, zmin, zmax)
            if (zmin, zmax) not in coll:
                coll.append((zmin, zmax))
            d.coll = coll.index((zmin, zmax))
            d.vertices = m.pixel_vertices(block, ppm)
            dynamic.append(d)
    return dynamic, coll


def _extent(dynamic):
    """The cell box (x0, y0, x1, y1) of the moving blocks at their start."""
    if not dynamic:
        return (0, 0, 0, 0)
    xs = np.concatenate([d.vertices[0] for d in dynamic])
    ys = np.concatenate([d.vertices[1] for d in dynamic])
    return (int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max()))


def _assign_blocks(robots, dynamic):
    """Each robot's blocks in the grid (indices into dynamic), per model of its tree."""
    by_model = {}
    for k, d in enumerate(dynamic):
        by_model.setdefault(id(d.model), []).append(k)
    for r in robots:
        blocks = [(m, by_model.get(id(m), [])) for m in _tree(r.model)]
        r.blocks = [(m, ks) for m, ks in blocks if ks]
        r.block_ids = np.array([k for _, ks in r.blocks for k in ks], np.int64)


def _draw_at_start(space, robots):
    """The load-time drawings, in model order, in both layers (sequence = the model's index):
    each layer's in one batch (a cell's entries in each layer come in the same order)."""
    blocks, poses, seqs = [], [], []
    for r in robots:
        for m, ks in r.blocks:
            blocks.extend(ks)
            poses.extend([body_row(m)] * len(ks))
            seqs.extend([m.index] * len(ks))
    if blocks:
        blocks = np.array(blocks, np.int64)
        poses = np.array(poses, np.float64)
        seqs = np.array(seqs, np.int64)
        for layer in (0, 1):
            space.draw(blocks, poses, layer, seqs)


def _overlaps(path, models, robots, space):
    """A warning when robots start overlapping a wall or another body (too many robots
    for the floor, a pose on a wall): Stage loads such a world and rejects every move that
    ends in a collision, so they do not move until what they overlap has moved away (a
    wall never does). Bodies are drawn by their outlines (MapPoly): a robot wholly inside
    a thick wall overlaps nothing, in Stage as here."""
    stuck = []
    for r in robots:
        hit = space.collides(r.block_ids, 0) if len(r.block_ids) else grid.NO_HIT
        if hit != grid.NO_HIT:
            stuck.append((r, hit))
    if not stuck:
        return []
    r, hit = stuck[0]
    what = {grid.STATIC: 'a wall', grid.GROUND: 'the ground'}.get(hit)
    what = what or models[hit].root.token
    return ['%s: %d of %d robots start overlapping a wall or another body (the first: %s,'
            ' on %s); as in Stage, they cannot move until it has moved away' % (
                path, len(stuck), len(robots), r.model.token, what)]


def _tree(model):
    """The model and every model it carries, depth first, itself first."""
    out = [model]
    for c in model.children:
        out.extend(_tree(c))
    return out


def _top_error(wf, name, what):
    p = wf.prop(0, name)
    return WorldError(p.path if p else wf.path, p.line if p else None, what)
