"""Runs a roslaunch on a private master: convoy_demo and the convoy and go-to-goal benches.

PrivateMasterLaunch owns the roslaunch process (any package's launch file: the go-to-goal
bench launches pioneer_mover's), a course_common ChildProcess like convoy.recording's
rosbag recorder, which records the run.
"""
import os
import time

import rosgraph
from course_common.ports import free_port
from course_common.processes import ChildProcess
from course_common.waiting import wait_for

POLL_S = 0.05  # condition polling period (wait_for's poll_s): the harness waits for seconds
STOP_TIMEOUT_S = 20.0  # roslaunch needs a few seconds to stop its nodes and master


class HarnessError(RuntimeError):
    """The launch could not be started or did not reach an expected state."""


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


class PrivateMasterLaunch(ChildProcess):
    """A roslaunch of any launch file with its own master on a free port; a context manager.

    Sets ROS_MASTER_URI (and ROS_LOG_DIR) in this process's environment, so a rospy node
    initialised afterwards joins that master.
    """

    def __init__(self, launch_args, log_path, port=None):
        super().__init__(log_path=log_path, stop_timeout_s=STOP_TIMEOUT_S)
        self.port = port or free_port()
        self.master_uri = 'http://localhost:%d' % self.port
        self.launch_args = launch_args
        self.started_at = None

    def start(self):
        os.environ['ROS_MASTER_URI'] = self.master_uri
        os.environ.setdefault('ROS_LOG_DIR', os.path.join(os.path.dirname(self.log_path),
                                                          'ros_log'))
        self.started_at = time.monotonic()
        super().start(['roslaunch', '-p', str(self.port)] + self.launch_args)
        master = rosgraph.Master('/convoy_harness', master_uri=self.master_uri)
        wait_for(master.is_online, 30.0, 'the master at %s' % self.master_uri, POLL_S,
                 alive=self.alive)
        return self
