"""rosbag's recorder as a child process: how convoy_demo records a run to a bag.

The bag, not code of ours, holds the run: any ROS tool (rosbag info/play, rqt_bag,
bag_report) reads it, and the demo's table and figures are made from it afterwards.
"""
import os
import subprocess

from convoy.harness import interrupt

STOP_TIMEOUT_S = 15.0  # the recorder flushes its buffer and writes the index on SIGINT
# rosbag stops recording with less than 1 GB free by default; a 30 s demo bag is about 1 MB.
MIN_FREE_SPACE = '100M'


def convoy_topics(n_robots):
    """Every pose and cmd_vel topic of a convoy of robot1..robot<n_robots>."""
    return ['/robot%d/%s' % (i, kind) for i in range(1, n_robots + 1)
            for kind in ('pose', 'cmd_vel')]


class BagRecorder:
    """`rosrun rosbag record -O BAG TOPICS` (the rosbag/record executable itself, so SIGINT
    reaches the process that closes the bag) with its output in a log file.

    Joins the master of ROS_MASTER_URI in this process's environment. Topics may appear later:
    the recorder subscribes to them by name.
    """

    def __init__(self, bag_path, topics, log_path, node_name='convoy_bag_record'):
        self.bag_path = bag_path
        self.topics = topics
        self.log_path = log_path
        self.node_name = node_name
        self._proc = None
        self._log = None

    def start(self):
        for stale in (self.bag_path, self.bag_path + '.active'):
            if os.path.exists(stale):
                os.remove(stale)  # a bag of an earlier run must not pass for this one
        self._log = open(self.log_path, 'w')  # noqa: SIM115 (closed in stop())
        self._proc = subprocess.Popen(
            ['rosrun', 'rosbag', 'record', '--min-space', MIN_FREE_SPACE, '-O', self.bag_path,
             '__name:=%s' % self.node_name] + self.topics,
            stdout=self._log, stderr=subprocess.STDOUT, env=dict(os.environ),
            start_new_session=True)
        return self

    def alive(self):
        return self._proc is not None and self._proc.poll() is None

    def exited(self):
        """True when the recorder was started and has ended on its own (not through stop())."""
        return self._proc is not None and self._proc.poll() is not None

    def receiving(self, master, topics):
        """True once each of `topics` has a publisher and this recorder among its subscribers,
        as `master` (a rosgraph.Master) sees the graph."""
        publishers, subscribers, _ = master.getSystemState()
        pubs, subs = dict(publishers), dict(subscribers)
        node = '/' + self.node_name
        return all(pubs.get(topic) and node in subs.get(topic, []) for topic in topics)

    def stop(self):
        """SIGINT (the recorder closes the bag), escalating to SIGKILL after STOP_TIMEOUT_S.

        Returns the recorder's exit code (None if it had to be killed or never started).
        Idempotent."""
        if self._proc is None:
            return None
        code = interrupt(self._proc, STOP_TIMEOUT_S)
        self._log.close()
        self._proc = None
        return code
