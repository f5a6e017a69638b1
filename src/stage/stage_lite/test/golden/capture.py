#!/usr/bin/python3
"""Capture what a stageros publishes through ROS, step by step, into one .npz.

    capture.py --stageros real|ours --world W.world --out OUT.npz
               [--gui] [--script SCRIPT.json] [--until SIM_SECONDS] [--exe PATH]

`real` is Stage 4.3.0 + stage_ros 1.8.0 built from source in scratch space (REAL_STAGEROS),
`ours` this workspace's stageros (stage_lite), from its devel space. Run it under
/usr/bin/python3 with the workspace sourced (`source /work/main/devel/setup.bash`); see
README.md beside it. compare.py compares two captures.

How it works, in order:
- a ROS master runs in this process, on a free port (ROS_HOSTNAME=localhost), with no
  /stageros parameters left over;
- stageros is started on the world, headless (-g) or with its window on a private Xvfb
  (--gui), with `_base_watchdog_timeout:=0` unless the script sets a watchdog;
- the master holds stageros's registration of its `reset_positions` service, the last thing
  both stageros do before their world starts stepping (stage_ros's SubscribeModels,
  stage_lite's StageServices). Meanwhile this process finds the robots among stageros's
  topics, subscribes to every odom, base_pose_ground_truth, base_scan* and /clock
  (tcp_nodelay, no queue limit, the raw bytes kept, decoded after the run), and advertises
  the cmd_vel topics the script drives (latched). Only once stageros lists a connection to
  this process on each of its topics is the call let through: nothing from the first step on
  is missed, even with real Stage running flat out headless. (stage_lite's rospy cannot
  connect its cmd_vel subscribers meanwhile: rospy makes one master call at a time, and one
  is held; so each command waits for its subscriber instead, before it is published);
- the script's actions are run at their simulated times (read from /clock), until the last
  step has arrived on every topic; stageros, the Xvfb and the master are then stopped (also
  on any failure);
- each message is indexed by its step, round(stamp / interval_sim) (the world's
  `interval_sim`, default 100 ms). A step missing or twice on any topic, or a stamp off the
  step grid, fails the capture: no .npz is written. A topic whose first message comes later
  than the others' (real stageros publishes no scan before its ranger's first update) has
  NaN rows before it; meta's `late_topics` lists them.

The script (JSON) is a list of actions, times in simulated seconds:
    {"t": 1.0, "robot": 0, "cmd": [vx, vy, wz]}   publish that Twist on robot 0's cmd_vel
    {"t": 5.0, "reset": true}                     call reset_positions
    {"until": 25.0}                               the last step recorded (or "t" with "until": true)
    {"watchdog": 0.2}                             ~base_watchdog_timeout (default 0: off); with a
                                                  watchdog, the last command of each robot is
                                                  published again at every step
Commands are latched publications. Without a script (and without --until) the first 5 steps
are recorded.

The .npz: `steps` (int32, the step indices, consecutive), per robot r (its N in /robot_N, 0
with one robot): `r<r>_odom_pose`, `r<r>_odom_twist`, `r<r>_gt_pose`, `r<r>_gt_twist` (float64,
(steps, 3): x, y, yaw from the quaternion / twist linear x, y and angular z), per ranger k
(`base_scan` is 0, `base_scan_<k>` is k): `r<r>_scan<k>_ranges`, `r<r>_scan<k>_intensities`
(float32, (steps, beams)), `r<r>_scan<k>_geom` (float64, (steps, 4): angle_min,
angle_increment, range_min, range_max); and `meta`, a JSON text (world, which stageros, gui,
date, commits, topics, script, when each action ran).
"""
import argparse
import contextlib
import datetime
import hashlib
import json
import os
import subprocess
import sys
import threading
import time
import xmlrpc.client
from pathlib import Path

import numpy as np

try:
    import rosgraph
    import rosgraph.xmlrpc
    import rospy
    from capture_record import STAMP_OFFSET, CaptureError, Recorder, capture_arrays, robot_topics
    from course_common.processes import ChildProcess
    from course_common.waiting import WaitError, wait_for
    from course_common.xvfb import Xvfb
    from geometry_msgs.msg import Twist
    from rosmaster.master_api import ROSMasterHandler
    from stage_lite.model.worldfile import Worldfile
    from std_srvs.srv import Empty
except ImportError as import_error:
    sys.exit('capture.py: %s (run it with /usr/bin/python3 after '
             '`source /work/main/devel/setup.bash`)' % import_error)

WORKSPACE = Path(__file__).resolve().parents[5]
REAL_STAGEROS = '/work/scratch/peer/src/stage_ws/devel/lib/stage_ros/stageros'
OURS_STAGEROS = str(WORKSPACE / 'devel' / 'lib' / 'stage_ros' / 'stageros')
STAGE_COMMIT = 'edddcb017940c9d8d98800370a764098cc55a1a7'  # rtv/Stage v4.3.0
STAGE_ROS_COMMIT = 'c3abc19b9e9713fe450597ca33b6f5399d1691ca'  # stage_ros lunar-devel, 1.8.0

NODE = '/stage_capture'  # this process's node
STAGEROS = '/stageros'  # both stageros' node name
DEFAULT_INTERVAL_MS = 100.0  # Stage's interval_sim default
DEFAULT_UNTIL_STEPS = 5  # without a script: the first 5 steps
START_TIMEOUT_S = 90.0  # stageros up to its reset_positions; real Stage loads big bitmaps slowly
CONNECT_TIMEOUT_S = 30.0  # every connection made, on a loaded 2-core machine
SIM_S_DEADLINE = 4.0  # wall s allowed per sim s (both run at real time or faster; load)
STOP_TIMEOUT_S = 10.0  # SIGINT to stageros, then SIGKILL


# --- inputs ---------------------------------------------------------------------------------
def world_interval_ns(world_path):
    """The world's interval_sim (ms in the file) in ns, else Stage's 100 ms, read as Stage
    reads it (stage_lite.model.worldfile: includes and macros too); the stamps of the
    capture are then checked against it."""
    ms = Worldfile(world_path).read_float(0, 'interval_sim', DEFAULT_INTERVAL_MS)
    return int(round(ms * 1e6))


class Script:
    """A script's actions sorted by time, its end (sim s or None) and watchdog (sim s)."""

    def __init__(self, entries=()):
        self.actions, self.until_s, self.watchdog_s = [], None, 0.0
        for entry in entries:
            if 'watchdog' in entry:
                self.watchdog_s = float(entry['watchdog'])
            elif 'until' in entry:
                self.until_s = float(entry['t'] if entry['until'] is True else entry['until'])
            elif 'cmd' in entry:
                vx, vy, wz = (float(v) for v in entry['cmd'])
                self.actions.append({'t': float(entry['t']), 'robot': int(entry['robot']),
                                     'cmd': [vx, vy, wz]})
            elif entry.get('reset'):
                self.actions.append({'t': float(entry['t']), 'reset': True})
            else:
                raise CaptureError('script: an action of no known kind: %r' % (entry,))
        self.actions.sort(key=lambda a: a['t'])

    @classmethod
    def load(cls, path):
        if path is None:
            return cls()
        try:
            return cls(json.loads(Path(path).read_text()))
        except (OSError, ValueError, KeyError, TypeError) as err:
            raise CaptureError('script %s: %s' % (path, err)) from None

    def robots(self):
        return sorted({a['robot'] for a in self.actions if 'cmd' in a})


# --- the master -----------------------------------------------------------------------------
class GatedMasterHandler(ROSMasterHandler):
    """rosmaster's own handler, except that stageros's registration of reset_positions waits
    until `release` is set: stageros's world does not step before this process is ready."""

    def __init__(self):
        super().__init__()
        self.held = threading.Event()  # stageros is waiting at the gate
        self.release = threading.Event()
        self.reset_service = None

    def registerService(self, caller_id, service, service_api, caller_api):  # noqa: N802
        if caller_id == STAGEROS and service.endswith('/reset_positions'):
            self.reset_service = service
            self.held.set()
            self.release.wait(START_TIMEOUT_S + CONNECT_TIMEOUT_S)
        return super().registerService(caller_id, service, service_api, caller_api)


class PrivateMaster:
    """A ROS master in this process on a free port (the kernel's pick); a context manager."""

    def __init__(self):
        self.handler = GatedMasterHandler()
        self._node = rosgraph.xmlrpc.XmlRpcNode(0, self.handler)
        self._node.start()
        self.uri = wait_for(lambda: self._node.uri, 10.0, 'the private master to bind')

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.handler.release.set()
        self._node.shutdown('capture done')


def stageros_lists(topics):
    """True once stageros's getBusInfo shows a connection to this node on every topic."""
    try:
        uri = rosgraph.Master(NODE).lookupNode(STAGEROS)
        code, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo(NODE)
    except (rosgraph.MasterError, OSError, xmlrpc.client.Fault):
        return False
    out = {c[4] for c in info if c[1] == NODE and c[2] == 'o'}
    return code == 1 and set(topics) <= out


# --- metadata -------------------------------------------------------------------------------
def git(folder, *args):
    """git's output in folder ('' outside a repository)."""
    return subprocess.run(['git', '-C', str(folder)] + list(args), capture_output=True,
                          text=True, check=False).stdout.strip()


def stage_lite_source():
    """Which stage_lite `ours` ran: the one this environment imports (stageros gets the same
    environment): its source folder, that repository's commit and changed files, and a sha1
    of its .py files (the workspace may be mid-edit)."""
    import stage_lite  # here: only for ours; the devel package's __path__ holds the source's

    folder = next(Path(p) for p in stage_lite.__path__
                  if (Path(p) / 'node' / 'stageros_node.py').is_file())
    digest = hashlib.sha1()
    for path in sorted(folder.rglob('*.py')):
        digest.update(str(path.relative_to(folder)).encode() + b'\0' + path.read_bytes())
    return {'path': str(folder), 'commit': git(folder, 'rev-parse', 'HEAD'),
            'changes': git(folder, 'status', '--porcelain', '--', '.').splitlines(),
            'sha1': digest.hexdigest()}


def metadata(args, exe, argv, interval_ns, script, topics, late, done, first_wall):
    world = Path(args.world).resolve()
    return {
        'world': str(world), 'world_sha1': hashlib.sha1(world.read_bytes()).hexdigest(),
        'stageros': args.stageros, 'executable': exe, 'argv': argv, 'gui': args.gui,
        'date': datetime.datetime.now(datetime.UTC).isoformat(timespec='seconds'),
        'workspace_commit': git(WORKSPACE, 'rev-parse', 'HEAD'),
        'stage_lite': stage_lite_source() if args.stageros == 'ours' else None,
        'stage_commit': STAGE_COMMIT, 'stage_ros_commit': STAGE_ROS_COMMIT,
        'interval_sim_ms': interval_ns / 1e6, 'watchdog_s': script.watchdog_s,
        'script': script.actions, 'actions_done': done,
        'topics': {t: 'r%d_%s' % rk for t, rk in sorted(topics.items())},
        'late_topics': late,
        'wall_s': round(time.monotonic() - first_wall, 2),
    }


# --- the run --------------------------------------------------------------------------------
def waiter(stageros):
    """wait(predicate, timeout_s, what): wait_for while stageros runs; CaptureError with its
    exit status and last lines if it ends or the deadline passes first."""
    def wait(predicate, timeout_s, what):
        try:
            return wait_for(predicate, timeout_s, what, alive=stageros.alive)
        except WaitError as err:
            code = stageros.returncode
            status = ('running' if code is None else 'killed by signal %d' % -code if code < 0
                      else 'exit code %d' % code)
            raise CaptureError('%s\nstageros (%s) printed, last lines:\n%s'
                               % (err, status, stageros.tail())) from None
    return wait


def run_actions(script, recorder, interval_ns, pubs, commands, reset_service, wait):
    """Runs each action once /clock has reached its time; returns when each ran (its /clock
    step). commands: each robot's last command (robot -> Twist), updated here."""
    done = []
    for action in script.actions:
        target = round(action['t'] * 1e9 / interval_ns)
        wait(lambda t=target: recorder.last_step['/clock'] >= t,
             CONNECT_TIMEOUT_S + SIM_S_DEADLINE * action['t'], 'sim time %g s' % action['t'])
        if 'cmd' in action:
            pub = pubs[action['robot']]
            wait(pub.get_num_connections, CONNECT_TIMEOUT_S, 'stageros to subscribe to %s'
                 % pub.resolved_name)
            vx, vy, wz = action['cmd']
            msg = Twist()
            msg.linear.x, msg.linear.y, msg.angular.z = vx, vy, wz
            commands[action['robot']] = msg
            pub.publish(msg)
        else:
            rospy.ServiceProxy(reset_service, Empty)()
        done.append(dict(action, clock_step=recorder.last_step['/clock']))
    return done


def capture(args):
    """Runs stageros on the world and returns (arrays, meta) of the capture."""
    started = time.monotonic()
    interval_ns = world_interval_ns(args.world)
    script = Script.load(args.script)
    until_s = args.until or script.until_s or DEFAULT_UNTIL_STEPS * interval_ns / 1e9
    last = round(until_s * 1e9 / interval_ns)
    exe = args.exe or (REAL_STAGEROS if args.stageros == 'real' else OURS_STAGEROS)
    argv = [exe] + ([] if args.gui else ['-g']) + [
        '_base_watchdog_timeout:=%r' % script.watchdog_s, os.path.abspath(args.world)]
    os.environ['ROS_HOSTNAME'] = 'localhost'
    env = {'PATH': '/usr/bin:' + os.environ.get('PATH', ''), 'DISPLAY': None}
    with contextlib.ExitStack() as stack:
        master = stack.enter_context(PrivateMaster())
        os.environ['ROS_MASTER_URI'] = env['ROS_MASTER_URI'] = master.uri
        params = rosgraph.Master(NODE)
        if params.hasParam(STAGEROS):  # a private param of an earlier run would change this one
            params.deleteParam(STAGEROS)
        rospy.init_node(NODE[1:], disable_rosout=True, disable_signals=True)
        stack.callback(rospy.signal_shutdown, 'capture done')
        if args.gui:
            env['DISPLAY'] = stack.enter_context(Xvfb()).display
        log = str(Path(args.out).with_suffix('')) + '.stageros.log'
        stageros = stack.enter_context(ChildProcess(argv, env=env, log_path=log,
                                                    stop_timeout_s=STOP_TIMEOUT_S))
        stack.callback(master.handler.release.set)  # a stageros held at the gate can stop
        wait = waiter(stageros)
        wait(master.handler.held.is_set, START_TIMEOUT_S, 'stageros to register reset_positions')
        state = params.getSystemState()
        published = {t for t, nodes in state[0] if STAGEROS in nodes}
        subscribed = {t for t, nodes in state[1] if STAGEROS in nodes}
        topics = robot_topics(published)
        if not topics:
            raise CaptureError('stageros publishes no robot topic: %s' % sorted(published))
        recorder = Recorder(interval_ns)
        for topic in sorted(topics):
            recorder.subscribe(topic, STAMP_OFFSET)
        recorder.subscribe('/clock', 0)
        pubs = {}
        for robot in script.robots():
            odom = next((t for t, rk in topics.items() if rk == (robot, 'odom')), None)
            cmd_vel = odom and odom[:-len('odom')] + 'cmd_vel'
            if cmd_vel not in subscribed:
                raise CaptureError('the script drives robot %d: stageros has no %s'
                                   % (robot, cmd_vel))
            pubs[robot] = rospy.Publisher(cmd_vel, Twist, queue_size=10, latch=True)
        commands = {}
        if script.watchdog_s > 0:  # keep the watchdog fed: every command again at every step
            recorder.on_clock = lambda step: [pubs[r].publish(m) for r, m in list(commands.items())]
        wait(lambda: stageros_lists(recorder.raw), CONNECT_TIMEOUT_S,
             'stageros to connect to this node on every topic')
        master.handler.release.set()  # the world starts stepping
        done = run_actions(script, recorder, interval_ns, pubs, commands,
                           master.handler.reset_service, wait)
        wait(lambda: recorder.reached(last), CONNECT_TIMEOUT_S + SIM_S_DEADLINE * until_s,
             'step %d on every topic' % last)
        recorder.unsubscribe()
    arrays, late = capture_arrays(recorder, topics, last)
    meta = metadata(args, exe, argv, interval_ns, script, topics, late, done, started)
    return arrays, meta


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--stageros', choices=('real', 'ours'), required=True)
    parser.add_argument('--world', required=True, help='the world file')
    parser.add_argument('--out', required=True, help='the .npz to write')
    parser.add_argument('--gui', action='store_true', help='with its window, on a private Xvfb')
    parser.add_argument('--script', help='timed actions (JSON), see the docstring')
    parser.add_argument('--until', type=float, help='last sim second recorded (default: the '
                        "script's until, else %d steps)" % DEFAULT_UNTIL_STEPS)
    parser.add_argument('--exe', help='the stageros executable (default: %s or %s)'
                        % (REAL_STAGEROS, OURS_STAGEROS))
    args = parser.parse_args(argv)
    if not os.path.isfile(args.world):
        parser.error('no world file %s' % args.world)  # real stageros would segfault
    if not os.path.isdir(os.path.dirname(os.path.abspath(args.out))):
        parser.error('no folder for %s' % args.out)
    return args


def main(argv=None):
    args = parse_args(argv)
    try:
        arrays, meta = capture(args)
    except (CaptureError, WaitError) as err:
        sys.exit('capture.py: %s' % err)
    arrays['meta'] = np.array(json.dumps(meta))
    np.savez_compressed(args.out, **arrays)
    n = len(arrays['steps'])
    print('capture.py: %s stageros, %s: steps %d..%d (%d) of %d topics, %.1f s -> %s'
          % (args.stageros, args.world, arrays['steps'][0], arrays['steps'][-1], n,
             len(meta['topics']), meta['wall_s'], args.out))
    if meta['late_topics']:
        print('capture.py: %d topics start later (rows before are NaN), at steps %s'
              % (len(meta['late_topics']), sorted(set(meta['late_topics'].values()))))


if __name__ == '__main__':
    main()
