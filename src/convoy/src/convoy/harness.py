"""Runs a convoy launch file on a private master (used by convoy_demo and the bench).

LaunchedConvoy owns the roslaunch process, a ChildProcess like convoy.recording's rosbag
recorder, which records the run.
"""
import os
import signal
import socket
import subprocess
import time

import rosgraph
from course_common.testing import wait_for

POLL_S = 0.05  # condition polling period (wait_for's poll_s): the harness waits for seconds
STOP_TIMEOUT_S = 20.0  # roslaunch needs a few seconds to stop its nodes and master


class HarnessError(RuntimeError):
    """The convoy could not be started or did not reach an expected state."""


def free_port():
    """A TCP port that is free right now on localhost (for a private master)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(('localhost', 0))
        return sock.getsockname()[1]


def launch_for(n_robots, gui=False, markers=False):
    """roslaunch arguments for an autopilot convoy of n_robots (the course file for 3).

    markers: also tf and what the rviz view draws (the demo's rviz picture).
    """
    extra = ['gui:=%s' % ('true' if gui else 'false')] + (['markers:=true'] if markers else [])
    if n_robots == 3:
        return ['convoy', 'convoy.launch', 'autopilot:=true'] + extra
    return ['convoy', 'convoy_chain.launch', 'n:=%d' % n_robots, 'autopilot:=true'] + extra


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
        wait_for(master.is_online, 30.0, 'the master at %s' % self.master_uri, POLL_S,
                 alive=self.alive)
        return self
