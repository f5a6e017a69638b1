"""Follows every turtle's pose topic on the master: subscribes on spawn, drops on kill.

ROS glue shared by pose_to_tf and lesson_markers, with the parameters they share
(WatchParams); the choice of topics is course_common.pose_topics'.
"""

import threading
from dataclasses import dataclass

import rospy
from course_common.param_loader import get_private
from course_common.params import check_name, check_namespace, check_number
from course_common.pose_topics import pose_topics
from turtlesim.msg import Pose

from turtle_lite.team_frames import diff_topics

QUEUE_SIZE = 1  # only the newest pose of each turtle matters to tf and to rviz


@dataclass(frozen=True)
class WatchParams:
    """What a node that follows the team reads first, validated: the tf frame the turtles'
    poses are in (~parent_frame), the namespace they are followed below (~namespace) and how
    often the master is asked (~discovery_period_s, s)."""

    parent_frame: str
    namespace: str
    discovery_period_s: float


def load_watch_params():
    """~parent_frame (str, "world"), ~namespace (str, "/": every simulator) and
    ~discovery_period_s (float > 0, 0.5 s). Raises ParamError naming the bad one."""
    return WatchParams(
        parent_frame=check_name('~parent_frame', get_private('parent_frame', 'world')),
        namespace=check_namespace('~namespace', get_private('namespace', '/')),
        discovery_period_s=check_number(
            '~discovery_period_s', get_private('discovery_period_s', 0.5), low=0.0, low_open=True))


class PoseWatch:
    """Polls the master every params.discovery_period_s for turtlesim/Pose topics below
    params.namespace (only the turtles named in only, when it names any).

    Calls on_pose(frame, msg, stamp) for each pose (stamp: rospy.Time of arrival) and
    on_gone(frame) when a topic leaves the master (the turtle was killed, or its simulator
    stopped). The master is the one place that knows every simulator's turtles, whoever
    spawned them; polling it also finds turtles spawned before this node started.
    """

    def __init__(self, params, only, on_pose, on_gone):
        self._namespace = params.namespace
        self._only = tuple(only)
        self._on_pose = on_pose
        self._on_gone = on_gone
        self._lock = threading.Lock()
        self._topics = {}
        self._subs = {}
        self.poll()
        self._timer = rospy.Timer(rospy.Duration(params.discovery_period_s),
                                  lambda _event: self.poll())

    def frames(self):
        with self._lock:
            return sorted(self._topics.values())

    def poll(self):
        """One look at the master: subscribe to new pose topics, drop the ones gone."""
        try:
            published = rospy.get_published_topics()
        except Exception as exc:
            rospy.logwarn_throttle(10.0, 'cannot list topics on the master: %s', exc)
            return
        found = pose_topics(published, self._namespace, self._only)
        with self._lock:
            added, removed = diff_topics(self._topics, found)
            gone = []
            for topic in removed:
                self._subs.pop(topic).unregister()
                gone.append(self._topics.pop(topic))
            for topic, frame in added.items():
                self._topics[topic] = frame
                self._subs[topic] = rospy.Subscriber(
                    topic, Pose, self._callback, callback_args=(topic, frame),
                    queue_size=QUEUE_SIZE)
        for frame in gone:
            rospy.loginfo('turtle %s gone', frame)
            self._on_gone(frame)
        for topic, frame in sorted(added.items()):
            rospy.loginfo('turtle %s: following %s', frame, topic)

    def _callback(self, msg, topic_frame):
        topic, frame = topic_frame
        # A pose already in flight when the turtle was dropped must not bring it back.
        if topic in self._topics:  # a dict lookup: atomic under the GIL, no lock needed
            self._on_pose(frame, msg, rospy.Time.now())

    def shutdown(self):
        self._timer.shutdown()
        with self._lock:
            for sub in self._subs.values():
                sub.unregister()
            self._subs.clear()
