"""turtlesim_node: turtlesim's simulator node, in rospy (same names, numbers, logs, quirks).

Node ``turtlesim`` (default name).

Node services (node namespace, like turtlesim):
  clear (std_srvs/Empty), reset (std_srvs/Empty), spawn (turtlesim/Spawn),
  kill (turtlesim/Kill)
Private services (turtle_lite extension):
  ~save_image (turtle_lite/SaveImage): write the canvas with the turtles as a PNG
Per turtle, in the turtle's namespace (``turtle1/...``; namespace remaps such as
``/turtle1:=/robot1`` move all six, as in roscpp):
  Subscribes  cmd_vel (geometry_msgs/Twist, queue 1)
  Publishes   pose (turtlesim/Pose), color_sensor (turtlesim/Color), every tick (62.5 Hz)
  Services    set_pen, teleport_relative, teleport_absolute
Parameters:
  ~background_r, ~background_g, ~background_b (int, default 69, 86, 255): written at start if
      absent, read only when the canvas is cleared (start, clear, reset); masked to 8 bits.
  ~gui (bool, default false): open a Tk window "TurtleSim" (falls back to headless with a WARN).
  ~image_path (str, default ~/.ros/turtle_lite.png): where ~save_image writes for an empty path.
  ~save_image_on_shutdown (bool, default false): write ~image_path when the node shuts down.
"""

import collections
import contextlib
import math
import os
import struct
import threading
import time
from dataclasses import dataclass

import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty, EmptyResponse
from turtlesim.msg import Color, Pose
from turtlesim.srv import (
    Kill,
    KillResponse,
    SetPen,
    SetPenResponse,
    Spawn,
    SpawnResponse,
    TeleportAbsolute,
    TeleportAbsoluteResponse,
    TeleportRelative,
    TeleportRelativeResponse,
)

from turtle_lite.frames import send_frame
from turtle_lite.srv import SaveImage, SaveImageResponse

from . import namespaces
from .naming import NameCounter, graph_name_error
from .world import CENTER, DEFAULT_BACKGROUND, DT_S, MAX_ABS_VELOCITY, World

#: TCPROS frames of turtlesim/Pose (5 float32) and turtlesim/Color (3 uint8): a
#: little-endian uint32 length, then the fields in order (the md5sums fix this layout).
_POSE_FRAME = struct.Struct('<I5f')
_POSE_BYTES = 20
_COLOR_FRAME = struct.Struct('<I3B')
_COLOR_BYTES = 3
DEFAULT_IMAGE_PATH = '~/.ros/turtle_lite.png'
#: Throttle period of the WARNs about bad input (a bad publisher can repeat at any rate).
BAD_INPUT_WARN_PERIOD_S = 1.0
#: If the tick thread falls this many periods behind (machine suspended or overloaded) it
#: re-anchors its schedule instead of firing a burst of catch-up ticks, as a Qt timer does.
MAX_LAG_TICKS = 4
#: On shutdown, how long to wait for rospy to finish its hooks, then how long to give its
#: XML-RPC thread to send the reply to the shutdown request (rospy itself sleeps 0.1 s).
SHUTDOWN_REPLY_WAIT_S = 0.4
SHUTDOWN_REPLY_GRACE_S = 0.15


@dataclass(frozen=True)
class SimParams:
    """The node's own settings (read once at start; the background is read on clear)."""

    gui: bool = False
    image_path: str = DEFAULT_IMAGE_PATH
    save_image_on_shutdown: bool = False


def _typed_param(name, default, kind):
    """Private param ``name`` if it has type ``kind``, else WARN and ``default``."""
    value = rospy.get_param('~' + name, default)
    ok = isinstance(value, kind) and not (kind is int and isinstance(value, bool))
    if kind is str:
        ok = ok and bool(value)
    if not ok:
        rospy.logwarn('Parameter ~%s=%r is not a %s; using the default %r',
                      name, value, kind.__name__, default)
        return default
    return value


def load_params():
    return SimParams(gui=_typed_param('gui', False, bool),
                     image_path=_typed_param('image_path', DEFAULT_IMAGE_PATH, str),
                     save_image_on_shutdown=_typed_param('save_image_on_shutdown', False, bool))


def _bad_values(limit=math.inf, **values):
    """'name=value' for each value that is not finite or beyond +-limit ('' if none)."""
    return ', '.join('%s=%r' % (k, v) for k, v in values.items()
                     if not math.isfinite(v) or abs(v) > limit)


def _tick_publisher(name, msg_class):
    """A publisher that the tick thread writes to synchronously.

    rospy's queue_size wraps every connection in a QueuedConnection: one thread per
    subscriber, woken for each message, plus a sleep(0) per write. At 62.5 Hz per turtle
    that dominated the node's CPU, so the tick thread writes the frames itself, never
    blocking (see _write_frame).
    Setting the impl's queue size after construction avoids rospy's warning about a missing
    queue_size; connections made from now on are plain transports.
    """
    pub = rospy.Publisher(name, msg_class, queue_size=1)
    pub.impl.queue_size = None
    return pub


class TurtleHandle:
    """The six ROS resources of one turtle, created from already-resolved full names."""

    def __init__(self, sim, name, resources):
        self.name = name
        self.resources = resources
        self.pose_pub = self.color_pub = self.cmd_sub = None
        self.services = []
        try:
            self.pose_pub = _tick_publisher(resources['pose'], Pose)
            self.color_pub = _tick_publisher(resources['color_sensor'], Color)
            for key, srv_class, handler in (
                    ('set_pen', SetPen, sim.handle_set_pen),
                    ('teleport_relative', TeleportRelative, sim.handle_teleport_relative),
                    ('teleport_absolute', TeleportAbsolute, sim.handle_teleport_absolute)):
                self.services.append(rospy.Service(
                    resources[key], srv_class,
                    lambda req, handler=handler: handler(self.name, req)))
            # Subscribe last, once everything the callback touches exists.
            self.cmd_sub = rospy.Subscriber(resources['cmd_vel'], Twist,
                                            lambda msg: sim.handle_cmd_vel(self.name, msg),
                                            queue_size=1)
        except Exception:
            self.unregister()  # e.g. a service name already taken: leave nothing behind
            raise

    def unregister(self):
        """Remove all six resources from the master (turtlesim's NodeHandle going away)."""
        parts = [self.cmd_sub, self.pose_pub, self.color_pub]
        actions = [p.unregister for p in parts if p is not None]
        actions += [srv.shutdown for srv in self.services]
        for action in actions:
            try:
                action()
            except Exception as exc:
                rospy.logdebug('while unregistering turtle [%s]: %s', self.name, exc)


class WallLog:
    """Logs turtlesim's wall WARNs from its own thread, in order.

    turtlesim warns on every tick for every turtle pushing against a wall; a rospy log line
    costs a few hundred microseconds (console, file, /rosout), so with many turtles at the
    walls logging from the tick thread would slow the 62.5 Hz tick itself. If the logger
    falls more than MAX_BACKLOG lines behind, the oldest are dropped and counted.
    """

    MAX_BACKLOG = 5000

    def __init__(self):
        self._queue = collections.deque()
        self._cond = threading.Condition()
        self._dropped = 0
        self._stopped = False
        self._thread = threading.Thread(target=self._run, name='turtlesim_walls', daemon=True)

    def start(self):
        self._thread.start()

    def stop(self):
        with self._cond:
            self._stopped = True
            self._cond.notify()

    def post(self, hits):
        with self._cond:
            self._queue.extend(hits)
            while len(self._queue) > self.MAX_BACKLOG:
                self._queue.popleft()
                self._dropped += 1
            self._cond.notify()

    def _run(self):
        while True:
            with self._cond:
                while not self._queue and not self._stopped:
                    self._cond.wait()
                if self._stopped:
                    return
                hits = list(self._queue)
                self._queue.clear()
                dropped, self._dropped = self._dropped, 0
            if dropped:
                rospy.logwarn('(%d wall warnings dropped: too many turtles at the walls)',
                              dropped)
            for hit in hits:
                rospy.logwarn('Oh no! I hit the wall! (Clamping from [x=%f, y=%f])',
                              hit.x, hit.y_s)


class TurtleSimNode:
    """Owns the world, the ROS interface of every turtle and the 62.5 Hz tick thread."""

    def __init__(self, params):
        self.params = params
        self.node_name = rospy.get_name()
        self.namespace = namespaces.node_namespace(self.node_name)
        self.mappings = dict(rospy.names.get_mappings())
        self._lock = threading.Lock()          # the world and the turtle handles
        self._svc_lock = threading.RLock()     # spawn / kill / reset / clear, one at a time
        self._pending_cmds = {}
        self._handles = {}
        self.counter = NameCounter()
        self._stop = threading.Event()
        self._thread = None
        self._wall_log = WallLog()
        self._reset_pool = None  # handles a reset may give back to the new turtle1
        self.tick_count = 0

        # turtlesim's start-up order (TURTLESIM.md 1.5).
        self._ensure_background_params()
        self.world = World(self._read_background())
        self._node_services = [
            rospy.Service('clear', Empty, self.handle_clear),
            rospy.Service('reset', Empty, self.handle_reset),
            rospy.Service('spawn', Spawn, self.handle_spawn),
            rospy.Service('kill', Kill, self.handle_kill),
            rospy.Service('~save_image', SaveImage, self.handle_save_image),
        ]
        rospy.loginfo('Starting turtlesim with node name %s', self.node_name)
        self.spawn('', CENTER, CENTER, 0.0)

    # ------------------------------------------------------------------ params
    @staticmethod
    def _ensure_background_params():
        for channel, default in zip('rgb', DEFAULT_BACKGROUND, strict=True):
            key = '~background_' + channel
            if not rospy.has_param(key):
                rospy.set_param(key, default)

    @staticmethod
    def _read_background():
        """The background params, or the built-in defaults for missing or non-int ones."""
        rgb = []
        for channel, default in zip('rgb', DEFAULT_BACKGROUND, strict=True):
            key = '~background_' + channel
            value = rospy.get_param(key, default)
            if isinstance(value, bool) or not isinstance(value, int):
                rospy.logwarn('Parameter %s=%r is not an int; using the default %d',
                              rospy.resolve_name(key), value, default)
                value = default
            rgb.append(value & 0xFF)  # Qt keeps the low 8 bits of each channel
        return tuple(rgb)

    # ------------------------------------------------------------------ turtles
    def spawn(self, name, x, y, theta):
        """Spawn a turtle like turtlesim's spawnTurtle; returns the final name.

        Raises rospy.ServiceException (after logging turtlesim's ERROR text) on failure.
        """
        # turtle_lite's own check, first, so a refused spawn does not use up a number.
        bad = _bad_values(x=x, y=y, theta=theta)
        if bad:
            rospy.logwarn('Ignoring spawn of [%s]: %s is not a finite number', name, bad)
            raise rospy.ServiceException('spawn ignored: %s is not finite' % bad)
        with self._svc_lock:
            with self._lock:
                if not name:
                    real_name = self.counter.next_name(self.world)
                elif name in self.world:
                    rospy.logerr('A turtled named [%s] already exists', name)
                    raise rospy.ServiceException('')
                else:
                    real_name = name
            error = graph_name_error(real_name)
            if error is not None:
                rospy.logerr('Exception thrown while processing service call: %s', error)
                raise rospy.ServiceException(error)
            try:
                resources = namespaces.turtle_resources(real_name, self.namespace,
                                                        self.node_name, self.mappings)
                handle = self._reuse_or_create(real_name, resources)
            except Exception as exc:
                rospy.logerr('Exception thrown while processing service call: %s', exc)
                raise rospy.ServiceException(str(exc)) from exc
            with self._lock:
                self.world.add_turtle(real_name, x, y, theta)
                self._handles[real_name] = handle
            rospy.loginfo('Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]',
                          real_name, x, y, theta)
            return real_name

    def _reuse_or_create(self, name, resources):
        pool = self._reset_pool
        if pool:
            for i, old in enumerate(pool):
                if old.resources == resources:
                    del pool[i]
                    old.name = name
                    return old
        return TurtleHandle(self, name, resources)

    def kill(self, name):
        with self._svc_lock:
            with self._lock:
                if name not in self.world:
                    rospy.logerr('Tried to kill turtle [%s], which does not exist', name)
                    raise rospy.ServiceException('')
                self.world.remove_turtle(name)
                handle = self._handles.pop(name)
                self._pending_cmds.pop(name, None)
            handle.unregister()

    def reset(self):
        with self._svc_lock:
            rospy.loginfo('Resetting turtlesim.')
            with self._lock:
                self.world.remove_all()
                old = list(self._handles.values())
                self._handles.clear()
                self._pending_cmds.clear()
                self.counter.reset()
            # A turtle1 on the very same names keeps its publishers, so subscribers that
            # were connected before the reset (draw_square, rqt) keep receiving. Every other
            # turtle's resources are unregistered from the master.
            self._reset_pool = old
            try:
                self.spawn('', CENTER, CENTER, 0.0)
            finally:
                leftovers, self._reset_pool = self._reset_pool, None
                for handle in leftovers:
                    handle.unregister()
            self.clear()

    def clear(self):
        background = self._read_background()
        with self._lock:
            self.world.clear(background)

    # ------------------------------------------------------------------ service handlers
    def handle_spawn(self, req):
        return SpawnResponse(self.spawn(req.name, req.x, req.y, req.theta))

    def handle_kill(self, req):
        self.kill(req.name)
        return KillResponse()

    def handle_clear(self, _req):
        with self._svc_lock:
            rospy.loginfo('Clearing turtlesim.')
            self.clear()
        return EmptyResponse()

    def handle_reset(self, _req):
        self.reset()
        return EmptyResponse()

    def _with_turtle(self, name, action):
        with self._lock:
            if name not in self.world:  # killed while the request was in flight
                raise rospy.ServiceException('turtle [%s] no longer exists' % name)
            action()

    def handle_set_pen(self, name, req):
        self._with_turtle(name, lambda: self.world.set_pen(name, req.r, req.g, req.b,
                                                           req.width, req.off))
        return SetPenResponse()

    def handle_teleport_absolute(self, name, req):
        bad = _bad_values(x=req.x, y=req.y, theta=req.theta)
        if bad:
            rospy.logwarn_throttle(BAD_INPUT_WARN_PERIOD_S,
                                   'Ignoring teleport_absolute of [%s]: %s is not a finite '
                                   'number' % (name, bad))
            raise rospy.ServiceException('teleport ignored: %s is not finite' % bad)
        self._with_turtle(name, lambda: self.world.teleport_absolute(name, req.x, req.y,
                                                                     req.theta))
        return TeleportAbsoluteResponse()

    def handle_teleport_relative(self, name, req):
        bad = _bad_values(linear=req.linear, angular=req.angular)
        if bad:
            rospy.logwarn_throttle(BAD_INPUT_WARN_PERIOD_S,
                                   'Ignoring teleport_relative of [%s]: %s is not a finite '
                                   'number' % (name, bad))
            raise rospy.ServiceException('teleport ignored: %s is not finite' % bad)
        self._with_turtle(name, lambda: self.world.teleport_relative(name, req.linear,
                                                                     req.angular))
        return TeleportRelativeResponse()

    def handle_cmd_vel(self, name, msg):
        vx, vy, w = msg.linear.x, msg.linear.y, msg.angular.z
        bad = _bad_values(MAX_ABS_VELOCITY, **{'linear.x': vx, 'linear.y': vy, 'angular.z': w})
        if bad:
            rospy.logwarn_throttle(BAD_INPUT_WARN_PERIOD_S,
                                   'Ignoring cmd_vel for [%s]: %s is not a finite number '
                                   'within +-%g' % (name, bad, MAX_ABS_VELOCITY))
            return
        # Applied at the next tick, like roscpp's queue of 1 drained by spinOnce. Under the
        # lock: the tick swaps the dict out, and a write into the old one would be lost.
        with self._lock:
            self._pending_cmds[name] = (vx, vy, w)

    def handle_save_image(self, req):
        path = req.path or self.params.image_path
        try:
            written = self.save_image(path)
        except (OSError, ValueError) as exc:
            rospy.logerr('Could not save the image to [%s]: %s', path, exc)
            raise rospy.ServiceException('could not save image: %s' % exc) from exc
        rospy.loginfo('Saved the canvas to [%s]', written)
        return SaveImageResponse(written)

    # ------------------------------------------------------------------ pictures
    def snapshot(self):
        """(canvas pixels copy, [(x, y, theta), ...]) for pictures and the window."""
        with self._lock:
            pixels = self.world.canvas.pixels.copy()
            poses = [(p[0], p[1], p[2]) for p in self.world.poses_now().tolist()]
        return pixels, poses

    def view_key(self):
        """Changes whenever the picture would: canvas version and turtle poses."""
        with self._lock:
            return self.world.canvas.version, self.world.poses_now().tobytes()

    def save_image(self, path):
        from .picture import save_png  # Pillow only when a picture is wanted
        pixels, poses = self.snapshot()
        return save_png(os.path.abspath(os.path.expanduser(path)), pixels, poses)

    # ------------------------------------------------------------------ ticking
    def start(self):
        self._wall_log.start()
        self._thread = threading.Thread(target=self._run, name='turtlesim_tick', daemon=True)
        self._thread.start()

    def stop(self, wait=True):
        self._stop.set()
        self._wall_log.stop()
        if wait and self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout=1.0)

    def _run(self):
        next_tick = time.monotonic()
        while not self._stop.is_set():
            next_tick += DT_S
            delay = next_tick - time.monotonic()
            if delay > 0.0:
                # A plain sleep is cheaper than Event.wait; stop() is seen within a tick.
                time.sleep(delay)
                if self._stop.is_set():
                    break
            elif delay < -MAX_LAG_TICKS * DT_S:
                next_tick = time.monotonic()
            try:
                self._tick()
            except Exception as exc:
                if self._stop.is_set() or rospy.is_shutdown():
                    break
                rospy.logerr_throttle(1.0, 'turtlesim tick failed: %r' % exc)

    def _tick(self):
        now = time.time()
        with self._lock:
            pending, self._pending_cmds = self._pending_cmds, {}
            for name, (vx, vy, w) in pending.items():
                if name in self.world:
                    self.world.set_command(name, vx, vy, w, now)
            self.tick_count += 1
            if self.tick_count == 1:
                return  # turtlesim's first tick only records the time
            result = self.world.step(now)
            handles = [self._handles.get(n) for n in result.names]
        if result.wall_hits:
            self._wall_log.post(result.wall_hits)
        poses = None
        colors = None
        for i, handle in enumerate(handles):
            if handle is None:
                continue
            if handle.pose_pub.impl.connections:
                if poses is None:
                    poses = result.poses.tolist()
                _write_frame(handle.pose_pub, _POSE_FRAME.pack(_POSE_BYTES, *poses[i]))
            if handle.color_pub.impl.connections:
                if colors is None:
                    colors = result.colors.tolist()
                _write_frame(handle.color_pub, _COLOR_FRAME.pack(_COLOR_BYTES, *colors[i]))


def _write_frame(pub, frame):
    """Send one ready-made TCPROS frame to every subscriber of ``pub``.

    This is what rospy's _PublisherImpl.publish does after serialising, without the
    per-call checks, buffer juggling and message object: the tick sends up to 62.5 x 2 x N
    messages a second and that overhead was most of the node's CPU. Unlike rospy's blocking
    sendall, a subscriber that stops reading only loses frames (as with roscpp's queue of 1)
    and never stalls the tick; a connection that fails, or took half a frame, is closed.
    """
    impl = pub.impl
    if impl is None or impl.closed:
        return  # unregistered (killed) between the step and the publish
    for conn in impl.connections:
        try:
            if send_frame(conn.socket, frame):
                conn.stat_bytes += len(frame)
                conn.stat_num_msg += 1
        except Exception:
            with contextlib.suppress(Exception):
                impl.remove_connection(conn)
                conn.close()


def _cheap_rosout():
    """Make each rospy log line cheaper without touching the parameter server.

    For every line, rospy's /rosout handler looks up /rosout_disable_topics_generation
    (an XML-RPC call to the master while the param is unset) and, unless it is true, lists
    every topic of the node into the Log message: 3 per turtle. Seeding rospy's local
    parameter cache with true skips both; Log.topics is then empty, which only rqt_console's
    topic column shows.
    """
    from rospy.impl.paramserver import get_param_server_cache
    get_param_server_cache().set(rospy.resolve_name('/rosout_disable_topics_generation'), True)


def main():
    rospy.init_node('turtlesim')
    _cheap_rosout()
    params = load_params()
    sim = TurtleSimNode(params)
    done = threading.Event()

    def on_shutdown(reason):
        # rospy prints its own line; these are roscpp's, which turtlesim shows on rosnode kill.
        if reason.startswith('external shutdown request'):
            rospy.logwarn('Shutdown request received.')
            detail = reason.rsplit(': ', 1)[-1].strip('[]')
            rospy.logwarn('Reason given for shutdown: [%s]', detail)
        sim.stop(wait=False)
        if params.save_image_on_shutdown:
            try:
                path = sim.save_image(params.image_path)
                rospy.loginfo('Saved the canvas to [%s]', path)
            except (OSError, ValueError) as exc:
                rospy.logerr('Could not save the image to [%s]: %s', params.image_path, exc)
        done.set()

    rospy.core.add_preshutdown_hook(on_shutdown)
    sim.start()
    if params.gui:
        from .gui import run_window  # tkinter and ImageTk only when the window is wanted
        run_window(sim, done)
    while not done.wait(0.1):
        pass
    # Let rospy finish its shutdown and answer the shutdown request (rosnode kill) before
    # the interpreter exits: exiting mid-reply makes rosnode report a connection error.
    deadline = time.monotonic() + SHUTDOWN_REPLY_WAIT_S
    while not rospy.core.is_shutdown() and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(SHUTDOWN_REPLY_GRACE_S)
