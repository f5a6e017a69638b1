"""A roslaunch with its own master on a free port: the demos and the benchmarks run on it.

A running `roscore` is left alone; the process that starts the launch joins its master
(ROS_MASTER_URI is set in its environment), so its own node and tools talk to that run.
"""
import os
import time

import rosgraph

from course_common.ports import free_port
from course_common.processes import ChildProcess
from course_common.waiting import wait_for

MASTER_TIMEOUT_S = 30.0  # roslaunch's own master, on a loaded 2-core machine
STOP_TIMEOUT_S = 20.0  # roslaunch needs a few seconds to stop its nodes and master
POLL_S = 0.05  # the master's answer is awaited for seconds: no need to poll finer


class PrivateMasterLaunch(ChildProcess):
    """`roslaunch -p PORT PKG FILE ARGS...` on a free port; a context manager (ChildProcess).

    launch_args: [package, launch file, arg:=value, ...]. env: changes to the launch's
    environment (a None value removes the variable: {'DISPLAY': None} runs it headless).
    start() sets ROS_MASTER_URI (and, unless set, ROS_LOG_DIR beside the log) in this
    process's environment, so a rospy node initialised afterwards joins that master, and
    waits until the master answers.
    """

    def __init__(self, launch_args, log_path, port=None, env=None):
        super().__init__(env=env, log_path=log_path, stop_timeout_s=STOP_TIMEOUT_S)
        self.port = port or free_port()
        self.master_uri = 'http://localhost:%d' % self.port
        self.launch_args = list(launch_args)
        self.started_at = None

    def start(self, argv=None):
        os.environ['ROS_MASTER_URI'] = self.master_uri
        os.environ.setdefault('ROS_LOG_DIR', os.path.join(os.path.dirname(self.log_path),
                                                          'ros_log'))
        self.started_at = time.monotonic()
        super().start(argv or ['roslaunch', '-p', str(self.port)] + self.launch_args)
        master = rosgraph.Master('/private_launch', master_uri=self.master_uri)
        wait_for(master.is_online, MASTER_TIMEOUT_S, 'the master at %s' % self.master_uri,
                 POLL_S, alive=self.alive)
        return self
