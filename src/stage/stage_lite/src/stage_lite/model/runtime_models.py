"""Models made while the world runs, as Stage 4.3's World::CreateModel, Model::SetPose,
SetGeom and SetColor make and change them (no rospy).

World::CreateModel(parent, type) runs the type's constructor and nothing of Load: a new
model has Stage's defaults (the unit square block, 1 m tall and not yet scaled to its size
[0.4 0.4 1.0], red, obstacle and ranger return on, 100 ms updates), its token made as at load
(`<parent token>.<type>:<n>`, n counting the parent's children of that type; `<type>:<n>` at
the top level, the ground model being model:0) and it is listed with the world's models;
it is not drawn into the grid until SetPose changes its pose or SetGeom sets its geometry:
both redraw it and its children (UnMapWithChildren, MapWithChildren) in both layers.

A model whose tree holds no robot stands still: its drawings join the static ones
(Space.replace_static, the finders' Sight, the cameras' scene, the floor's occupancy),
remade once before the next step however many models changed since. A model made before the
first step (a controller's init, as Stage's `dynamic`) is drawn exactly where Stage draws
it. Made during the run, it comes first in a cell where a robot's body drawn before it lies
too, until that robot's next move (Stage keeps draw order; here static drawings are ordered
by model index): rays through such a cell may differ for one step. A model made but never
posed nor sized is in no drawing, except the cameras' (their scene draws every static model).
A model made in a robot's tree (`dynamic` on a position model) rides on the robot, its
blocks the robot's (moved, drawn and tested for collisions with it): made, moved and resized
before the first step only, when the grid and the robots' kernels are made again, every
drawing then a load-time one in model order (Stage's order).
Not simulated: making a model of another type than `model` (a robot, a sensor), one in a
robot's tree after the first step, and moving or resizing a model a robot carries that the
world file made: each is one clear ValueError.
"""
import math
import os

import numpy as np

from . import world_load
from .models import Model
from .motion import Motion
from .pose import stage_normalize
from .sight import Sight
from .space import Space
from .world_load import BUILTIN_TYPES, _static_cells

#: The types World.create_model makes (Stage's typetable holds more: see BUILTIN_TYPES).
CREATABLE_TYPES = ('model',)


def create_model(world, parent, kind):
    """World::CreateModel: a new model of type `kind` under `parent` (a model, or None for
    the top level), listed last in the world's models; ValueError for what is not
    simulated, or a type Stage does not know (Stage exits: "Model type ... not found in
    model typetable")."""
    if kind not in BUILTIN_TYPES:
        raise ValueError('Model type %s not found in model typetable (Stage\'s types: %s)'
                         % (kind, ', '.join(BUILTIN_TYPES)))
    if kind not in CREATABLE_TYPES:
        raise ValueError('a %s made at run time is not simulated here (only %s)'
                         % (kind, ', '.join(CREATABLE_TYPES)))
    if parent is not None and _moves(world, parent) and world.updates:
        raise ValueError('%s moves (it is in robot %s\'s tree): models are made on a moving'
                         ' model before the first step only' % (parent.token,
                                                                 parent.root.token))
    world_dir = os.path.dirname(os.path.abspath(world.path))
    m = Model(world_dir, parent, kind, len(world.models), None, _top_counts(world))
    m.mapped = False                  # drawn from its first SetPose or SetGeom on
    _list(world, m)
    return m


def set_pose(world, model, pose):
    """Model::SetPose: the pose in its parent's frame (its angle normalised); a change
    redraws it and its children."""
    x, y, z, a = _finite(model, 'pose', pose)
    if (x, y, z, a) == tuple(model.pose):
        return
    _may_change(world, model, 'moved')
    model.pose = (x, y, z, stage_normalize(a))
    _redraw(world, model)


def set_geom(world, model, pose, size):
    """Model::SetGeom: the origin offset and size, its blocks scaled to it (CalcSize); it
    and its children redrawn."""
    pose = _finite(model, 'geom pose', pose)
    size = _finite(model, 'geom size', size)
    _may_change(world, model, 'resized')
    model.set_geom(pose, size)
    _redraw(world, model)


def set_color(world, model, color):
    """Model::SetColor: (r, g, b, a) in 0..1."""
    model.color = _finite(model, 'color', color)
    if world.cameras.scene is not None:       # the cameras' scene holds the colours
        world._statics_changed = True


def redraw_if_changed(world):
    """The static drawings remade (grid, finders, cameras, floor) if a model was made,
    moved or resized since they were last made; before a step."""
    statics_changed, trees_changed = world._statics_changed, world._trees_changed
    world._statics_changed = world._trees_changed = False
    if not (statics_changed or trees_changed):
        return
    moving = set(np.flatnonzero(world._robot_slot[world._root_of] >= 0).tolist())
    statics = [m for m in world.models
               if m.index not in moving and getattr(m, 'mapped', True)]
    cells = _static_cells(statics, set(), world.ppm)
    if trees_changed:
        _rebuild_grid(world, moving, cells)
    else:
        world.space.replace_static(cells)
    world._statics = statics
    world._static_cells = (cells[0].astype(np.int32), cells[1].astype(np.int32))
    world._occupancy = None
    world.sight = Sight(world.models, world.robots, world.space)
    if world.cameras.scene is not None:
        from .camera_render import Scene  # numba's kernels only when a world has cameras
        world.cameras.scene = Scene(world.models, moving, world.ppm)


def _rebuild_grid(world, moving, static_cells):
    """A new grid with the robots' trees as they now are (before the first step: every
    drawing is a load-time one, in model order, the models made since last), and the
    robots' kernels on it."""
    old = world.space
    drawn = [m for m in world.models if getattr(m, 'mapped', True)]
    dynamic, coll = world_load._moving_blocks(drawn, moving, world.ppm)
    space = Space(world.ppm, len(world.models), old.model_root, old.model_rr,
                  old.model_obstacle)
    space.build(static_cells, world._ray_zs, dynamic, coll, world_load._extent(dynamic))
    world_load._assign_blocks(world.robots, dynamic)
    world_load._draw_at_start(space, world.robots)
    world.space = space
    if world.motion is not None:
        world.motion = Motion(world.robots, space)


def _list(world, m):
    """The new model in every per-model table of the world (World::AddModel)."""
    world.models.append(m)
    world._robot_slot = np.append(world._robot_slot, -1)
    world._ranger_slot = np.append(world._ranger_slot, -1)
    world._root_of = np.append(world._root_of, m.root.index)
    for kind, mask in world._kind.items():
        world._kind[kind] = np.append(mask, False)
    world._rank[m] = max(world._rank.values(), default=-1) + 1
    world.stage_order.append(m)
    world._masks_version = None       # the per-model masks are remade at the next step
    world._model_chains = None
    world._static_poses.clear()       # World.global_poses's plans: rows of those chains
    tokens = world._models_by_token
    if tokens is not None:
        tokens[m.token] = m           # Stage's models_by_name: the latest of a name wins
    space = world.space
    space.model_root = np.append(space.model_root, m.root.index)
    space.model_rr = np.append(space.model_rr, m.ranger_return)
    space.model_obstacle = np.append(space.model_obstacle, m.obstacle_return)
    # its drawings come after every drawing so far (static ones are ordered by index)
    space.seq = max(space.seq, m.index)


def _top_counts(world):
    """World's child_type_counts: the top-level models of each type so far (the ground
    model is model:0)."""
    counts = world._top_counts
    if counts is None:
        counts = world._top_counts = {'model': 1}
        for m in world.models:
            if m.parent is None:
                counts[m.kind] = counts.get(m.kind, 0) + 1
    return counts


def _redraw(world, model):
    """MapWithChildren: it and its children drawn (at the next step's remaking)."""
    stack = [model]
    while stack:
        m = stack.pop()
        m.mapped = True
        stack.extend(m.children)
    if _moves(world, model):
        world._trees_changed = True
    else:
        world._statics_changed = True
        world._static_poses.clear()       # World.global_poses's, of static models
        world.energy.statics_moved()        # the static chargers' and takers' cells


def _moves(world, model):
    """Whether the model is in a robot's tree (it moves with the robot)."""
    return bool(world._robot_slot[world._root_of[model.index]] >= 0)


def _may_change(world, model, what):
    """A model a robot carries is moved or resized only if it was made at run time, and
    before the first step."""
    if not _moves(world, model):
        return
    if not hasattr(model, 'mapped') or world.updates:
        raise ValueError('%s is in robot %s\'s tree: a carried model is %s only if made at'
                         ' run time, before the first step' % (model.token,
                                                                model.root.token, what))


def _finite(model, what, values):
    values = tuple(float(v) for v in values)
    if not all(math.isfinite(v) for v in values):
        raise ValueError('%s: %s must be finite, got %r' % (model.token, what, values))
    return values
