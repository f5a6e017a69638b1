"""rosbag's recorder as a child process: how convoy_demo records a run to a bag.

The bag, not code of ours, holds the run: any ROS tool (rosbag info/play, rqt_bag,
bag_report) reads it, and the demo's table and figures are made from it afterwards.
"""
import os

from course_common.processes import ChildProcess

# rosbag stops recording with less than 1 GB free by default; a 30 s demo bag is about 1 MB.
MIN_FREE_SPACE = '100M'


def convoy_topics(n_robots):
    """Every pose and cmd_vel topic of a convoy of robot1..robot<n_robots>."""
    return ['/robot%d/%s' % (i, kind) for i in range(1, n_robots + 1)
            for kind in ('pose', 'cmd_vel')]


class BagRecorder(ChildProcess):
    """`rosrun rosbag record -O BAG TOPICS` (the rosbag/record executable itself, so SIGINT
    reaches the process that closes the bag), its output in a log file; a context manager.

    Joins the master of ROS_MASTER_URI in this process's environment. Topics may appear later:
    the recorder subscribes to them by name.
    """

    def __init__(self, bag_path, topics, log_path, node_name='convoy_bag_record'):
        # The recorder flushes its buffer and writes the index on SIGINT.
        super().__init__(log_path=log_path, stop_timeout_s=15.0)
        self.bag_path = bag_path
        self.topics = topics
        self.node_name = node_name

    def start(self):
        for stale in (self.bag_path, self.bag_path + '.active'):
            if os.path.exists(stale):
                os.remove(stale)  # a bag of an earlier run must not pass for this one
        super().start(['rosrun', 'rosbag', 'record', '--min-space', MIN_FREE_SPACE,
                     '-O', self.bag_path, '__name:=%s' % self.node_name] + self.topics)
        return self

    def receiving(self, master, topics):
        """True once each of `topics` has a publisher and this recorder among its subscribers,
        as `master` (a rosgraph.Master) sees the graph."""
        publishers, subscribers, _ = master.getSystemState()
        pubs, subs = dict(publishers), dict(subscribers)
        node = '/' + self.node_name
        return all(pubs.get(topic) and node in subs.get(topic, []) for topic in topics)
