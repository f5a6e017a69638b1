"""turtlesim_node: turtlesim's simulator node, in rospy (same names, numbers, logs, quirks).

Node ``turtlesim`` (default name).

Node services (node namespace, like turtlesim):
  clear (std_srvs/Empty), reset (std_srvs/Empty), spawn (turtlesim/Spawn),
  kill (turtlesim/Kill)
Private services (turtle_lite extension):
  ~save_image (course_msgs/SaveImage): write the canvas with the turtles as a PNG
Per turtle, in the turtle's namespace (``turtle1/...``; namespace remaps such as
``/turtle1:=/robot1`` move all six, as in roscpp):
  Subscribes  cmd_vel (geometry_msgs/Twist, queue 1)
  Publishes   pose (turtlesim/Pose), color_sensor (turtlesim/Color), every tick (62.5 Hz)
  Services    set_pen, teleport_relative, teleport_absolute
Parameters:
  ~background_r, ~background_g, ~background_b (int, default 69, 86, 255): written at start if
      absent, read only when the canvas is cleared (start, clear, reset); masked to 8 bits.
  ~gui (bool, default: true when DISPLAY is set): open a Tk window "TurtleSim" (falls back to
    headless with a WARN).
  ~image_path (str, default ~/.ros/turtle_lite.png): where ~save_image writes for an empty path.
  ~save_image_on_shutdown (bool, default false): write ~image_path when the node shuts down.
"""

import contextlib
import math
import threading
import time

import rospy
from course_common.arena import SPAWN_M
from course_common.finite import is_finite_number
from course_common.graph_names import graph_name_error
from course_common.rospy_internals import add_preshutdown_hook, cheap_rosout, name_mappings
from course_common.save_image import answer_save_image, save_logged
from course_common.schedule import BAD_INPUT_WARN_PERIOD_S
from course_common.startup import init_node
from course_msgs.srv import SaveImage, SaveImageResponse
from std_srvs.srv import Empty, EmptyResponse
from turtlesim.srv import (
    Kill,
    KillResponse,
    SetPenResponse,
    Spawn,
    SpawnResponse,
    TeleportAbsoluteResponse,
    TeleportRelativeResponse,
)

from . import namespaces
from .naming import NameCounter
from .sim_params import ensure_background_params, load_params, read_background
from .tick_loop import TickLoop
from .tick_publish import publish_tick
from .turtle_handle import TurtleHandle
from .wall_log import WallLog
from .world import DT_S, MAX_ABS_VELOCITY, World

#: On shutdown, how long to wait for rospy to finish its hooks, then how long to give its
#: XML-RPC thread to send the reply to the shutdown request (rospy itself sleeps 0.1 s).
SHUTDOWN_REPLY_WAIT_S = 0.4
SHUTDOWN_REPLY_GRACE_S = 0.15


def _bad_values(limit=math.inf, **values):
    """'name=value' for each value that is not finite or beyond +-limit ('' if none)."""
    return ', '.join('%s=%r' % (k, v) for k, v in values.items()
                     if not is_finite_number(v) or abs(v) > limit)


class TurtleSimNode:
    """Owns the world, the ROS interface of every turtle and the 62.5 Hz tick thread."""

    def __init__(self, params):
        self.params = params
        self.node_name = rospy.get_name()
        self.namespace = namespaces.node_namespace(self.node_name)
        self.mappings = name_mappings()
        self._lock = threading.Lock()          # the world and the turtle handles
        self._svc_lock = threading.RLock()     # spawn / kill / reset / clear, one at a time
        self._pending_cmds = {}
        self._handles = {}
        self.counter = NameCounter()
        self._ticker = TickLoop(self._tick, DT_S, 'turtlesim_tick')
        self._wall_log = WallLog()
        self._reset_pool = None  # handles a reset may give back to the new turtle1
        self.tick_count = 0

        # turtlesim's start-up order (turtle_frame.cpp's TurtleFrame constructor).
        ensure_background_params()
        self.world = World(read_background())
        self._node_services = [
            rospy.Service('clear', Empty, self.handle_clear),
            rospy.Service('reset', Empty, self.handle_reset),
            rospy.Service('spawn', Spawn, self.handle_spawn),
            rospy.Service('kill', Kill, self.handle_kill),
            rospy.Service('~save_image', SaveImage, self.handle_save_image),
        ]
        rospy.loginfo('Starting turtlesim with node name %s', self.node_name)
        self.spawn('', SPAWN_M, SPAWN_M, 0.0)

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
                self.spawn('', SPAWN_M, SPAWN_M, 0.0)
            finally:
                leftovers, self._reset_pool = self._reset_pool, None
                for handle in leftovers:
                    handle.unregister()
            self.clear()

    def clear(self):
        background = read_background()
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
        return SaveImageResponse(answer_save_image(req.path, self.params.image_path,
                                                   self.save_image, 'canvas',
                                                   'could not save image'))

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
        """Writes the canvas and turtles to path (absolute); returns the path written."""
        from .picture import save_png  # Pillow only when a picture is wanted
        pixels, poses = self.snapshot()
        return save_png(path, pixels, poses)

    # ------------------------------------------------------------------ ticking
    # Called by the TickLoop every DT_S; the wall WARNs and the frames leave the lock.
    def start(self):
        self._wall_log.start()
        self._ticker.start()

    def stop(self, wait=True):
        self._ticker.stop()
        self._wall_log.stop()
        if wait:
            self._ticker.join(timeout_s=1.0)

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
        publish_tick(handles, result)


def main():
    init_node('turtlesim')
    cheap_rosout()
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
            with contextlib.suppress(OSError, ValueError):  # logged: the node still ends
                save_logged('', params.image_path, sim.save_image, 'canvas')
        done.set()

    add_preshutdown_hook(on_shutdown)
    sim.start()
    if params.gui:
        from .gui import run_window  # tkinter and ImageTk only when the window is wanted
        run_window(sim, done)
    while not done.wait(0.1):
        pass
    # Let rospy finish its shutdown and answer the shutdown request (rosnode kill) before
    # the interpreter exits: exiting mid-reply makes rosnode report a connection error.
    deadline = time.monotonic() + SHUTDOWN_REPLY_WAIT_S
    while not rospy.is_shutdown() and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(SHUTDOWN_REPLY_GRACE_S)
