"""Every turtle of a simulator as a tf frame: pose topics found on the master, pose -> transform.

No rospy. The nodes pass in what the master reports (``getPublishedTopics``: a list of
``[topic, type]``) and poses as plain numbers. Units are metres and radians; the transform is
the one the ROS tf2 tutorials broadcast for turtlesim: parent ``world``, translation
(x, y, 0), rotation the yaw theta about z.
"""

import math
from collections import namedtuple

from course_common.graph_names import normalize_namespace

#: The message type whose topics are turtles' poses (turtlesim's, ours is the same).
POSE_TYPE = 'turtlesim/Pose'
POSE_LEAF = 'pose'

Transform = namedtuple('Transform', 'x y z qx qy qz qw')
"""Translation (m) and unit quaternion (x, y, z, w) of a frame in its parent."""


def frame_for_pose_topic(topic, namespace='/'):
    """The frame name of a turtle's pose topic, or None when the topic is not one below namespace.

    '/robot1/pose' -> 'robot1'; with namespace '/turtlesim1', '/turtlesim1/turtle1/pose' ->
    'turtle1'; with namespace '/', the same topic gives 'turtlesim1/turtle1', so two
    simulators' turtle1 stay two frames. A bare '/pose' is no turtle's (no name).
    """
    ns = normalize_namespace(namespace)
    if not topic.startswith(ns):
        return None
    parts = topic[len(ns):].split('/')
    if len(parts) < 2 or parts[-1] != POSE_LEAF or not all(parts[:-1]):
        return None
    return '/'.join(parts[:-1])


def pose_topics(published, namespace='/', only=()):
    """{topic: frame} for the turtlesim/Pose topics below namespace in the master's list.

    published: iterable of (topic, type) pairs, as getPublishedTopics returns. only: frame
    names to keep (empty keeps all).
    """
    keep = set(only)
    found = {}
    for topic, msg_type in published:
        if msg_type != POSE_TYPE:
            continue
        frame = frame_for_pose_topic(topic, namespace)
        if frame is not None and (not keep or frame in keep):
            found[topic] = frame
    return found


def diff_topics(old, new):
    """(added, removed) between two {topic: frame} maps: added a dict, removed a sorted list.

    A topic whose frame changed (it cannot, for one namespace) counts as removed and added.
    """
    added = {t: f for t, f in new.items() if old.get(t) != f}
    removed = sorted(t for t, f in old.items() if new.get(t) != f)
    return added, removed


def pose_to_transform(x, y, theta):
    """The Transform of a turtle at (x, y) m heading theta rad. Raises ValueError if not finite."""
    for label, value in (('x', x), ('y', y), ('theta', theta)):
        if not isinstance(value, (int, float)) or isinstance(value, bool) \
                or not math.isfinite(value):
            raise ValueError('pose %s = %r: expected a finite number' % (label, value))
    half = 0.5 * theta
    return Transform(float(x), float(y), 0.0, 0.0, 0.0, math.sin(half), math.cos(half))
