"""Runs a convoy launch file on a private master and records it (used by convoy_demo and bench).

LaunchedConvoy owns the roslaunch process (a ChildProcess, like convoy.recording's rosbag
recorder of the demo); ConvoyRecorder is the bench's live recording node (rospy).
"""
import os
import signal
import socket
import subprocess
import threading
import time

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

POLL_S = 0.05  # condition polling period
STOP_TIMEOUT_S = 20.0  # roslaunch needs a few seconds to stop its nodes and master


class HarnessError(RuntimeError):
    """The convoy could not be started or did not reach an expected state."""


def wait_until(predicate, timeout_s, what, alive=None):
    """Polls predicate() until true; raises HarnessError naming `what` after timeout_s.

    `alive` (optional) is polled too: when it returns False the wait fails at once.
    """
    deadline = time.monotonic() + timeout_s
    while not predicate():
        if alive is not None and not alive():
            raise HarnessError('gave up waiting for %s: the launch exited' % what)
        if time.monotonic() > deadline:
            raise HarnessError('timed out after %.0f s waiting for %s' % (timeout_s, what))
        time.sleep(POLL_S)


def free_port():
    """A TCP port that is free right now on localhost (for a private master)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(('localhost', 0))
        return sock.getsockname()[1]


def launch_for(n_robots, gui=False):
    """roslaunch arguments for an autopilot convoy of n_robots (the course file for 3)."""
    gui_arg = 'gui:=%s' % ('true' if gui else 'false')
    if n_robots == 3:
        return ['convoy', 'convoy.launch', 'autopilot:=true', gui_arg]
    return ['convoy', 'convoy_chain.launch', 'n:=%d' % n_robots, 'autopilot:=true', gui_arg]


def convoy_node_names(n_robots):
    """Names of the convoy_node instances of launch_for(n_robots), follower 2 first."""
    if n_robots == 3:
        return ['/convoy_node', '/convoy2_node']
    return ['/convoy_robot%d' % i for i in range(2, n_robots + 1)]


class ChildProcess:
    """A child process in a session of its own, its stdout and stderr in a log file.

    stop() sends SIGINT (ROS tools then shut down cleanly: roslaunch stops its nodes and
    master, rosbag record closes its bag) and SIGKILLs the session after stop_timeout_s.
    """

    stop_timeout_s = STOP_TIMEOUT_S

    def __init__(self, log_path):
        self.log_path = log_path
        self._proc = None
        self._log = None

    def _spawn(self, args):
        self._log = open(self.log_path, 'w')  # noqa: SIM115 (closed in stop())
        self._proc = subprocess.Popen(args, stdout=self._log, stderr=subprocess.STDOUT,
                                      env=dict(os.environ), start_new_session=True)

    def alive(self):
        return self._proc is not None and self._proc.poll() is None

    def exited(self):
        """True when the process was started and has ended on its own (not through stop())."""
        return self._proc is not None and self._proc.poll() is not None

    def log_tail(self, lines=15):
        try:
            with open(self.log_path) as log:
                return ''.join(log.readlines()[-lines:])
        except OSError:
            return ''

    def stop(self):
        """SIGINT, then SIGKILL if needed; idempotent.

        Returns the exit code (None if it had to be killed or never started)."""
        if self._proc is None:
            return None
        code = self._proc.poll()
        if code is None:
            self._proc.send_signal(signal.SIGINT)
            try:
                code = self._proc.wait(self.stop_timeout_s)
            except subprocess.TimeoutExpired:
                os.killpg(self._proc.pid, signal.SIGKILL)
                self._proc.wait()
        self._log.close()
        self._proc = None
        return code

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


class LaunchedConvoy(ChildProcess):
    """A roslaunch of the convoy with its own master on a free port; a context manager.

    Sets ROS_MASTER_URI (and ROS_LOG_DIR) in this process's environment, so a rospy node
    initialised afterwards joins that master.
    """

    def __init__(self, launch_args, log_path, port=None):
        super().__init__(log_path)
        self.port = port or free_port()
        self.master_uri = 'http://localhost:%d' % self.port
        self.launch_args = launch_args
        self.started_at = None

    def start(self):
        os.environ['ROS_MASTER_URI'] = self.master_uri
        os.environ.setdefault('ROS_LOG_DIR', os.path.join(os.path.dirname(self.log_path),
                                                          'ros_log'))
        self.started_at = time.monotonic()
        self._spawn(['roslaunch', '-p', str(self.port)] + self.launch_args)
        master = rosgraph.Master('/convoy_harness', master_uri=self.master_uri)
        wait_until(master.is_online, 30.0, 'the master at %s' % self.master_uri, self.alive)
        return self


class ConvoyRecorder:
    """Records the poses (and optionally the commands) of robot1..robot<n>.

    Subscribes:
        /robot<i>/pose (turtlesim/Pose) for i = 1..n.
        /robot<i>/cmd_vel (geometry_msgs/Twist) for i = 2..n, if record_commands.
    Publishes, services, parameters: none.
    Samples are (t_s, x_m, y_m) with t from time.monotonic(); command receipt times pair with
    the newest follower pose received before them (the bench's latency).
    """

    def __init__(self, n_robots, record_commands=False):
        self.n_robots = n_robots
        self._lock = threading.Lock()
        self.poses = {i: [] for i in range(1, n_robots + 1)}
        self.first_moving = {}
        self.latencies_s = {i: [] for i in range(2, n_robots + 1)}
        self._recording = False
        self._last_pose_at = {}
        self._subs = [rospy.Subscriber('/robot%d/pose' % i, Pose, self._on_pose, i,
                                       queue_size=50)
                      for i in range(1, n_robots + 1)]
        if record_commands:
            self._subs += [rospy.Subscriber('/robot%d/cmd_vel' % i, Twist, self._on_cmd, i,
                                            queue_size=50)
                           for i in range(2, n_robots + 1)]

    def _on_pose(self, msg, robot):
        now = time.monotonic()
        with self._lock:
            self._last_pose_at[robot] = now
            if msg.linear_velocity > 0.0 and robot not in self.first_moving:
                self.first_moving[robot] = now
            if self._recording or not self.poses[robot]:
                self.poses[robot].append((now, msg.x, msg.y))

    def _on_cmd(self, _msg, robot):
        now = time.monotonic()
        with self._lock:
            pose_at = self._last_pose_at.get(robot)
            if self._recording and pose_at is not None:
                self.latencies_s[robot].append(now - pose_at)

    def all_seen(self):
        with self._lock:
            return all(self.poses.values())

    def start_recording(self):
        with self._lock:
            for samples in self.poses.values():
                del samples[:]
            self._recording = True

    def stop_recording(self):
        with self._lock:
            self._recording = False

    def close(self):
        for sub in self._subs:
            sub.unregister()
