"""Stage's plugin interface in Python: the models and the world as a controller sees them.

A controller (Stage's examples ported in stage_lite.controllers, or your own module, see
controllers.py) gets its model as one of these and calls what Stage's C++ controllers call,
under Python names: Subscribe() is subscribe(), AddCallback(Model::CB_UPDATE, f, arg) is
add_callback('update', f, arg), SetSpeed is set_speed, GetSensors()[0].ranges is
sensors[0].ranges, and so on (the table in the package README). Callbacks are called as
f(model, arg), model being the same object; one that returns a true value is removed, as in
Stage. No rospy.
"""
import math
from dataclasses import dataclass
from typing import NamedTuple

from . import runtime_models
from .bodies import rasterize
from .energy import find_power_pack
from .pose import pose_add, stage_normalize
from .robot_state import MODE_CODE
from .scheduler import CB_FLAGDECR, CB_FLAGINCR

AXES = {'x': 0, 'y': 1, 'z': 2, 'a': 3}     # a command's parts: their places in a goal


class Pose(NamedTuple):
    """Stage's Pose: x, y, z (m), a (rad). A named tuple: controllers make hundreds a step,
    and a tuple is made at half a frozen dataclass's cost."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    a: float = 0.0

    def __add__(self, other):
        """Stage's Pose + Pose: other in this pose's frame (not a tuple's concatenation)."""
        return Pose(*pose_add(self, other))

    @classmethod
    def random(cls, world, xmin, xmax, ymin, ymax):
        """Pose::Random: x in [xmin, xmax), y in [ymin, ymax), z 0, a random heading, from
        the world's drand48() stream. Stage's build draws the heading first, then y, then x
        (GCC evaluates the constructor's arguments right to left)."""
        a = stage_normalize(world.drand48() * (2.0 * math.pi))
        y = ymin + world.drand48() * (ymax - ymin)
        x = xmin + world.drand48() * (xmax - xmin)
        return cls(x, y, 0.0, a)


@dataclass
class Flag:
    """Stage's Model::Flag: what foraging robots pick up and drop, a colour and a size."""

    color: tuple = (1.0, 1.0, 0.0, 1.0)
    size: float = 0.25


class CtrlArgs:
    """Stage's CtrlArgs: `worldfile`, the whole ctrl string ("source 5"), and `cmdline`,
    the `stage -a` argument string (World::ctrlargs)."""

    def __init__(self, worldfile, cmdline):
        self.worldfile = worldfile
        self.cmdline = cmdline

    def words(self):
        """The ctrl string split on blanks: [name, arg1, ...]."""
        return self.worldfile.split()


class WorldApi:
    """The world a controller sees (one per World)."""

    def __init__(self, world):
        self._world = world

    @property
    def ctrlargs(self):
        return self._world.ctrlargs

    def sim_time_now(self):
        """Simulated time, microseconds (Stage's usec_t)."""
        return self._world.sim_time_us

    def update_count(self):
        return self._world.updates

    def get_model(self, name):
        """The model whose token (its name, or Stage's made-up `position:0.ranger:1`) is
        name, or None."""
        tokens = self._world._models_by_token
        if tokens is None:     # Stage's models_by_name: a later model of a name wins
            tokens = self._world._models_by_token = {m.token: m for m in self._world.models}
        m = tokens.get(name)
        return api_of(self._world, m) if m is not None else None

    def random(self):
        """glibc's random(), the stream Stage's own draws share."""
        return self._world.random.random()

    rand = random

    def random_stream(self):
        """random()'s stream itself (glibc_random.Random: its state arrays `table` and
        `pointers`), for a controller's batch that draws in a kernel (random_next)."""
        return self._world.random

    def random_block(self, count):
        """The next `count` values of random(), in order (an int64 array)."""
        return self._world.random.block(count)

    def srandom(self, seed):
        """srandom(seed): random()'s stream starts again from seed."""
        self._world.random.srandom(seed)

    @property
    def seed(self):
        """The world's seed (load_world's), None if it was given none."""
        return self._world.seed

    @property
    def clock_seed(self):
        """What Stage seeds from the clock (srand48(time), fasr2's srandom(time)): the run's
        number (load_world's run), else the world's seed; None if it was given neither."""
        return self._world.clock_seed

    def drand48(self):
        return self._world.rand48.drand48()

    def drand48_state(self):
        """drand48()'s state array, for a controller's batch that draws in a kernel
        (glibc_random.drand48_next)."""
        return self._world.rand48.state

    def create_model(self, parent, kind):
        """World::CreateModel: a new model of type `kind` (only 'model' is simulated) under
        parent (a model, or None), with Stage's defaults, not drawn until its pose or
        geometry is set (runtime_models.py); ValueError for what is not simulated."""
        m = runtime_models.create_model(self._world, None if parent is None
                                        else parent._model, kind)
        return api_of(self._world, m)

    def add_update_callback(self, function, argument=None):
        """World::AddUpdateCallback: f(world, arg) after every step's model callbacks."""
        self._world.scheduler.add_world_callback(lambda _, a: function(self, a), argument)


class ModelApi:
    """Stage's Model: its tree, pose, geometry, subscriptions, callbacks and flags."""

    def __init__(self, world, model):
        self._world = world
        self._model = model

    def __repr__(self):
        return '<%s %s>' % (type(self).__name__, self.token)

    @property
    def token(self):
        return self._model.token

    @property
    def type(self):
        return self._model.kind

    @property
    def world(self):
        return world_api(self._world)

    def get_world(self):
        return self.world

    @property
    def parent(self):
        p = self._model.parent
        return api_of(self._world, p) if p is not None else None

    @property
    def children(self):
        return [api_of(self._world, c) for c in self._model.children]

    def get_child(self, name):
        """Model::GetChild: the model named `<this token>.<name>`, or None."""
        return self.world.get_model('%s.%s' % (self.token, name))

    def get_unused_model_of_type(self, kind):
        """Model::GetUnusedModelOfType: this model or the first of its descendants (depth
        first) of that type not taken yet, now taken; None if there is none."""
        stack = [self._model]
        while stack:
            m = stack.pop(0)
            if m.kind == kind and not m.used:
                m.used = True
                return api_of(self._world, m)
            stack[0:0] = m.children
        return None

    # ---- pose and geometry -----------------------------------------------------------------
    def get_pose(self):
        return Pose(*self._model.pose)

    def get_global_pose(self):
        return Pose(*self._model.global_pose())

    def get_geom(self):
        """(origin Pose, size (x, y, z))."""
        return Pose(*self._model.geom_pose), tuple(self._model.geom_size)

    @property
    def color(self):
        return self._model.color

    def get_color(self):
        return self._model.color

    def set_pose(self, pose):
        """Model::SetPose: (x, y, z, a) in its parent's frame (a Pose or 4 numbers); a
        model that stands still only (runtime_models.py)."""
        runtime_models.set_pose(self._world, self._model, tuple(pose))

    def set_geom(self, pose, size):
        """Model::SetGeom: its origin offset (a Pose) and size (x, y, z), its body scaled to
        it; a model that stands still only."""
        runtime_models.set_geom(self._world, self._model, tuple(pose), tuple(size))

    def set_color(self, color):
        """Model::SetColor: (r, g, b, a), each 0..1."""
        runtime_models.set_color(self._world, self._model, tuple(color))

    def rasterize(self, width, height, cell_w, cell_h):
        """Model::Rasterize: the outlines of its blocks in a width x height raster of
        cell_w x cell_h m cells from its bottom left corner (bytearray, bottom row first)."""
        return rasterize(self._model.blocks, self._model.geom_size, width, height, cell_w,
                         cell_h)

    # ---- subscriptions and callbacks -------------------------------------------------------
    def subscribe(self):
        self._world.subscribe(self._model)

    def unsubscribe(self):
        self._world.unsubscribe(self._model)

    def add_callback(self, kind, function, argument=None):
        """Model::AddCallback: kind 'update', 'flag_incr', 'flag_decr', 'startup' or
        'shutdown'; function(model, argument). A function with a `batch` (see
        scheduler.py) may be called together with others of its batch."""
        self._world.scheduler.add_callback(self._model, kind, ApiCallback(self, function),
                                           argument)

    # ---- energy (energy.py) --------------------------------------------------------------
    def find_power_pack(self):
        """Model::FindPowerPack: its own power pack or its nearest ancestor's (stored,
        capacity, charging, dissipated, proportion_remaining()), or None."""
        return find_power_pack(self._model)

    def get_watts(self):
        return self._model.watts

    def set_watts(self, watts):
        """Model::SetWatts: what it draws from its pack while started."""
        self._model.watts = float(watts)

    # ---- flags ---------------------------------------------------------------------------
    def get_flag_count(self):
        return len(self._model.flags)

    def push_flag(self, flag):
        """Model::PushFlag: on top of its flags, a stack (flag_incr callbacks)."""
        if flag is not None:
            self._model.flags.append(flag)
            self._world.scheduler.call(self._model, CB_FLAGINCR)

    def pop_flag(self):
        """Model::PopFlag: the flag pushed last, removed (flag_decr callbacks); None if none."""
        if not self._model.flags:
            return None
        flag = self._model.flags.pop()
        self._world.scheduler.call(self._model, CB_FLAGDECR)
        return flag


class ApiCallback:
    """A controller's callback as the scheduler calls it, f(model, arg), with the model's
    handle for the controller; `function` is the controller's, `batch` its batch (or
    None)."""

    __slots__ = ('handle', 'function', 'batch')

    def __init__(self, handle, function):
        self.handle = handle
        self.function = function
        self.batch = getattr(function, 'batch', None)

    def __call__(self, _, argument):
        return self.function(self.handle, argument)


class PositionApi(ModelApi):
    """Stage's ModelPosition: commands (velocity, acceleration, position), its velocity,
    estimate and stall."""

    @property
    def _robot(self):
        return self._world.robot_of(self._model)

    def set_speed(self, x, y, a):
        self._command('velocity', x=x, y=y, z=0.0, a=a)

    def stop(self):
        """ModelPosition::Stop: set_speed(0, 0, 0)."""
        self.set_speed(0.0, 0.0, 0.0)

    def set_x_speed(self, x):
        self._command('velocity', x=x)

    def set_y_speed(self, y):
        self._command('velocity', y=y)

    def set_z_speed(self, z):
        self._command('velocity', z=z)

    def set_turn_speed(self, a):
        self._command('velocity', a=a)

    def set_acceleration(self, x, y, a):
        self._command('acceleration', x=x, y=y, z=0.0, a=a)

    def go_to(self, x, y, a):
        self._command('position', x=x, y=y, z=0.0, a=a)

    def _command(self, mode, **parts):
        for axis, value in parts.items():
            if not math.isfinite(value):
                raise ValueError('%s: %s %s must be finite, got %r'
                                 % (self.token, mode, axis, value))
        goal, modes, row = self._robot.command_rows()
        for axis, value in parts.items():
            goal[row, AXES[axis]] = float(value)
        modes[row] = MODE_CODE[mode]

    def get_velocity(self):
        return Pose(*self._robot.velocity)

    def get_goal(self):
        return Pose(*self._robot.goal)

    @property
    def est_pose(self):
        """The position model's estimate (odometry or gps)."""
        return Pose(*self._robot.est_pose)

    def stalled(self):
        return self._robot.stalled

    def command_rows(self):
        """(goal, mode, row): the world's arrays this robot's command lives in (goal[row] =
        (x, y, z, a), mode[row] a robot_state.MODE_CODE), for a controller's batch that
        commands many robots in one kernel as set_speed would."""
        return self._robot.command_rows()

    def pose_rows(self):
        """(pose, row): the world's array this model's pose lives in (pose[row] = (x, y, z,
        a), in its parent's frame, as get_pose gives it), for a controller's batch."""
        return self._model.pose_rows()


def world_api(world):
    if world._world_api is None:
        world._world_api = WorldApi(world)
    return world._world_api


def api_of(world, model):
    """The one handle of a model (made at first use)."""
    handles = world._handles
    handle = handles.get(model)
    if handle is None:
        # the sensors' handles build on ModelApi, in a module of their own
        from .stage_api_sensors import BlobfinderApi, FiducialApi, RangerApi
        cls = {'position': PositionApi, 'ranger': RangerApi, 'fiducial': FiducialApi,
               'blobfinder': BlobfinderApi}.get(model.kind, ModelApi)
        handle = handles[model] = cls(world, model)
    return handle


def normalize(angle):
    """Stage's normalize: an angle in [-pi, pi]."""
    return stage_normalize(angle)
