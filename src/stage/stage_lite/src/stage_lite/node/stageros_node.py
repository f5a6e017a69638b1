"""stageros: stage_ros 1.8.0's node on stage_lite's world (same names, types, frames, rates).

Usage: ``rosrun stage_ros stageros [-g] [-u] WORLD`` (node name ``stageros``). The robots
are the world's ``position`` models in file order; names: stage_lite.names.

Per robot (``/robot_<N>/...`` with several robots or -u, relative with one):
  Subscribes  cmd_vel (geometry_msgs/Twist, queue 10): x, y (omni only), angular z;
              NaN or infinite commands are refused with a throttled WARN.
  Publishes   odom (nav_msgs/Odometry): odometry pose, commanded twist, frame odom;
              base_pose_ground_truth (nav_msgs/Odometry): world pose, finite-difference twist;
              base_scan, or base_scan_<k> with several rangers (sensor_msgs/LaserScan;
              base_scan_<k> is absolute even for one robot: /base_scan_0);
              every step, stamped with sim time (stage_ros queues 10 per subscriber;
              here each step's frames are written at once, and a subscriber that cannot
              take one whole loses that message, as with a full roscpp queue);
              stall (std_msgs/Bool, latched, on change) with ~publish_stall only;
              per camera on the robot (camera_publish): image (sensor_msgs/Image, rgba8),
              depth (sensor_msgs/Image, 32FC1 m or 16UC1 mm), camera_info
              (sensor_msgs/CameraInfo), frame camera; image_<k>, depth_<k>, camera_info_<k>,
              camera_<k> (absolute) with several cameras.
Global:
  Publishes   /clock (rosgraph_msgs/Clock) every step, never 0; /tf (tf2_msgs/TFMessage) every
              step, one message: odom -> base_footprint -> base_link -> base_laser_link[_k]
              per robot, and base_link -> camera[_k] while its image or depth is subscribed;
              with ~publish_map: /map (nav_msgs/OccupancyGrid, latched, frame map)
              and /tf_static map -> every robot's odom (identity).
  Services    reset_positions (std_srvs/Empty): every robot to its start pose, stall cleared;
              ~save_image (course_msgs/SaveImage, with ~save_image_service only): a PNG of
              the world, robots, beams, trails.
  Sets        /use_sim_time true, before the world is loaded (before init_node when the
              master is up); the node's own rospy time follows the sim time it publishes.
Parameters (private):
  ~base_watchdog_timeout (float, 0.2, s of sim time): stop every robot when no cmd_vel came
      for that long (one time for all robots); <= 0 disables.
  ~speedup (float, the world's `speedup`, default 1): sim seconds per wall second; -1 = as
      fast as possible.
  ~tf2_frames (bool, false): frame ids without the leading '/' (tf2-clean).
  ~publish_stall (bool, false), ~odom_child_frame (bool, false: odom child_frame_id =
      base_footprint frame), ~publish_map (bool, false), ~map_resolution (float, 0.05, m),
  ~save_image_service (bool, false): offer ~save_image;
  ~image_path (str, ~/.ros/stage_lite.png): where ~save_image writes for an empty path.
  ~is_depth_canonical (bool, true): depth as 32FC1 metres (-inf/+inf out of range), else
      16UC1 millimetres (0 out of range), as stageros.
Command line: -g no window (without -g a Tk window opens when there is a display, else a
WARN and headless), -u model names as namespaces; the world file last.
"""
import os
import sys
import threading
import time
from dataclasses import replace

import rosgraph
import rospy
from course_common.param_loader import load_or_exit
from course_common.rospy_internals import (
    cheap_rosout,
    one_receive_thread,
    throttled_topic_checks,
)
from course_common.schedule import BAD_INPUT_WARN_PERIOD_S, Throttle
from course_common.startup import init_node

from ..view.status import RateMeter, clock_string
from ..view.world_picture import render
from ..view.world_view import WorldView
from . import wire
from .camera_publish import CameraOutputs
from .names import all_robot_names, shared_namespaces
from .pacing import SimClock, Watchdog, world_speedup
from .rospy_clock import drop_own_clock_subscription, set_own_time
from .stage_publish import StepOutput
from .stage_services import StageServices
from .stageros_args import ArgsError, parse_args
from .stageros_params import load_params
from .step_loop import StepLoop


class StageNode:
    """Owns the world, the ROS interface of every robot and the stepping thread."""

    def __init__(self, world, args, params):
        self.world = world
        self.args = args
        self.params = params
        self.lock = threading.Lock()      # the world, the clock, the watchdog
        self.clock = SimClock(world.interval_sim_s)
        self.watchdog = Watchdog(params.base_watchdog_timeout_s)
        self._warn = [Throttle(BAD_INPUT_WARN_PERIOD_S) for _ in world.robots]
        self.names = all_robot_names([r.model_name for r in world.robots],
                                     [len(r.rangers) for r in world.robots],
                                     args.use_model_names, params.tf2_frames)
        for line in shared_namespaces(self.names):
            rospy.logwarn(line)
        self.cameras = CameraOutputs(world, self.names, args.use_model_names,
                                     params.tf2_frames, params.is_depth_canonical)
        self.output = StepOutput(world, self.names, params, self.on_cmd_vel,
                                 self.on_cmd_vel_bodies, self.cameras)
        self.view = WorldView(world)
        self.rate = RateMeter()           # the real-time factor of the status line
        self.loop = StepLoop(self.step, world.interval_sim_s, node_speedup(world, params),
                             world.quit_time_s, self.output.wait_for_waiting_subscribers)
        self.services = StageServices(world, params, self.names, self.reset, self.picture)

    def on_cmd_vel(self, msg, index):
        self.command(index, msg.linear.x, msg.linear.y, msg.angular.z)

    def on_cmd_vel_bodies(self, bodies, index):
        """cmd_vel's messages as bodies (rospy_internals.deliver_bodies), oldest first."""
        for body in bodies:
            self.command(index, *wire.twist_command(body))

    def command(self, index, vx, vy, wz):
        """stageros's cmdvelReceived: the robot's speed, and the watchdog told."""
        try:
            with self.lock:
                self.world.set_command(index, vx, vy, wz)
                self.watchdog.command(self.clock.now_ns)
        except ValueError as err:
            if self._warn[index].ready(time.monotonic()):
                rospy.logwarn('Ignoring cmd_vel for %s: linear.x=%r, linear.y=%r, '
                              'angular.z=%r (%s)', self.names[index].cmd_vel, vx, vy, wz, err)

    def step(self):
        """One world step and its messages; called by the StepLoop. Returns the sim time, s."""
        with self.lock:
            self.world.step()
            self.clock.tick()
            stamp = self.clock.stamp()
            frames, stalls = self.output.collect(self.world, stamp)
            self.view.record()
            self.rate.add(time.monotonic(), self.clock.now_s)
            # After collecting: the odom of this step still shows the command it moved with,
            # as in stageros, where SetSpeed(0) takes effect at the next world update.
            if self.watchdog.expired(self.clock.now_ns):
                self.world.stop_all()
            now_s = self.clock.now_s
        self.output.send(frames, stalls)
        set_own_time(*stamp)
        return now_s

    def reset(self):
        """reset_positions: every robot to its start pose, its trail cleared."""
        with self.lock:
            self.world.reset()
            self.view.clear()

    def picture(self):
        """~save_image's picture: the window's drawing of the world's own view (its window
        block), with the robots' trails."""
        camera = self.view.camera()
        options = replace(self.view.options, trails=True)
        _, robots, status = self.snapshot()
        return render(camera, self.view.floor(camera, options.grid), robots, options, status)

    def snapshot(self):
        """(steps so far, the robots' views, the status line) taken under the lock, for the
        window and ~save_image."""
        with self.lock:
            status = clock_string(self.clock.now_ns, self.rate.factor(), self.loop.paused)
            return self.clock.steps, self.view.robots(), status

    def describe(self):
        w = self.world
        return ('%s: %d robot%s, interval_sim %g ms, %s, watchdog %s'
                % (w.path, len(w.robots), '' if len(w.robots) == 1 else 's',
                   w.interval_sim_s * 1000.0, self.loop.describe(),
                   ('%g s' % self.params.base_watchdog_timeout_s)
                   if self.params.base_watchdog_timeout_s > 0 else 'off'))


def node_speedup(world, params):
    """~speedup, else the world's `speedup` (pacing.world_speedup)."""
    return params.speedup if params.speedup is not None else world_speedup(world.speedup)


def _fatal(text):
    rospy.logfatal(text)
    sys.exit(1)


class WorldLoader(threading.Thread):
    """Loads the world file in a thread, while rospy registers the node with the master.

    Both take a while at start (numpy, the floor plan and its distance field; XML-RPC calls
    to the master), and the one waits on sockets while the other computes. An error becomes
    one line (``error``) for the FATAL log, never a traceback.
    """

    def __init__(self, path):
        super().__init__(name='stageros_world_load', daemon=True)
        self.path = path
        self.world = None
        self.error = None

    def run(self):
        try:
            # numpy and the model after the command line; inside the try: when a bad
            # parameter ends the process first, this import meets the interpreter's shutdown
            # (concurrent.futures' atexit refused), and that is no traceback either
            from ..model.world import WorldError, load_world
        except Exception as err:
            self.error = '%s: could not load the world: %s' % (self.path, err)
            return
        try:
            self.world = load_world(self.path)
        except WorldError as err:
            self.error = str(err)
        except Exception as err:  # an unreadable or odd file: one FATAL line, never a traceback
            self.error = '%s: could not load the world: %s' % (self.path, err)


def set_use_sim_time_early():
    """/use_sim_time true before init_node (and so before the world is loaded); False when
    the master cannot be reached yet (then it is set after init_node, before the load)."""
    try:
        rosgraph.Master('/stageros').setParam('/use_sim_time', True)
    except (OSError, rosgraph.MasterError):
        return False
    return True


def set_use_sim_time_when_the_master_is_up(retry_s=0.5):
    """/use_sim_time true once the master answers (a C++ node waits for it at start too)."""
    while not rospy.is_shutdown():
        try:
            rospy.set_param('/use_sim_time', True)
            return
        except OSError:
            time.sleep(retry_s)


def world_or_exit(loader):
    """The loaded world, or a FATAL line naming the file (and line) and exit 1."""
    loader.join()
    if loader.error is not None or loader.world is None:
        _fatal(loader.error or '%s: could not load the world' % loader.path)
    world = loader.world
    world.log = rospy.logerr      # a controller's callback that raises: one ERROR line
    if not world.robots:
        rospy.logwarn('%s: the world has no position models: no robot topics', world.path)
    for line in world.warnings + world.stageros_warnings:
        rospy.logwarn(line)
    return world


def main(argv=None):
    argv = rospy.myargv(argv=sys.argv if argv is None else argv)
    try:
        args = parse_args(argv[1:])
    except ArgsError as err:
        sys.stderr.write('[FATAL] stageros: %s\n' % err)
        sys.exit(1)
    exists = os.path.isfile(args.world_path)
    # Load while rospy registers (start-up time); /use_sim_time first, so that nodes starting
    # meanwhile see it (stage_ros #49). A missing world file sets nothing, as in stageros.
    loader = WorldLoader(args.world_path)
    if exists and set_use_sim_time_early():
        loader.start()
    throttled_topic_checks()  # thousands of topics: rospy's checks after each registration
    one_receive_thread()      # a cmd_vel connection a robot: one thread, not one each
    init_node('stageros')
    cheap_rosout()
    drop_own_clock_subscription()  # this node is the clock: it sets rospy's time itself
    params = load_or_exit(load_params, 'stageros')
    for extra in args.ignored:
        rospy.logwarn('stageros: ignoring the argument %r (usage: stageros [-g] [-u] WORLD)',
                      extra)
    if not exists:
        _fatal('The world file %s does not exist.' % args.world_path)
    if loader.ident is None:  # the master was not there before init_node
        set_use_sim_time_when_the_master_is_up()
        loader.start()
    world = world_or_exit(loader)
    node = StageNode(world, args, params)
    rospy.loginfo('stageros: %s', node.describe())
    node.loop.start()
    try:
        if args.gui:
            from ..view.gui import run_window  # tkinter only when a window is wanted
            run_window(world, node.view, node.snapshot, node.loop, lambda: node.clock.steps)
        rospy.spin()
    finally:
        node.loop.stop()
        node.loop.join(1.0)
