"""Which topics are robots' poses, and whose: the turtlesim/Pose '<robot>/pose' topics.

Pure (no rospy, no rosbag). The callers pass in a list of (topic, type) pairs, as the
master's getPublishedTopics or a bag's topic table gives them. A robot is named after the
namespace of its pose topic, relative to a namespace: '/robot2/pose' -> 'robot2'; below
'/turtlesim1', '/turtlesim1/turtle1/pose' -> 'turtle1' (from '/', 'turtlesim1/turtle1').
The maps go {topic: robot}, the way a subscriber needs them; a topic names one robot.
"""
from course_common.graph_names import normalize_namespace

#: The message type whose topics are robots' poses (turtlesim's; ours has the same md5sum).
POSE_TYPE = 'turtlesim/Pose'
#: The last name segment of a pose topic.
POSE_LEAF = 'pose'


def robot_of_pose_topic(topic, namespace='/'):
    """The robot whose pose `topic` is, relative to `namespace`; None if it is no robot's pose.

    A name without a leading '/' counts as global ('robot2/pose' is '/robot2/pose'): bags and
    the master hold global names. None for a topic outside namespace, one not ending in
    '/pose', a bare '/pose' (no robot) and empty segments ('/a//pose').
    ValueError if topic is not a string or namespace is not a valid namespace.
    """
    if not isinstance(topic, str):
        raise ValueError('topic = %r: expected a string such as /robot1/pose' % (topic,))
    ns = normalize_namespace(namespace)
    name = topic if topic.startswith('/') else '/' + topic
    if not name.startswith(ns):
        return None
    parts = name[len(ns):].split('/')
    if len(parts) < 2 or parts[-1] != POSE_LEAF or not all(parts[:-1]):
        return None
    return '/'.join(parts[:-1])


def pose_topics(published, namespace='/', only=()):
    """{topic: robot} of the POSE_TYPE pose topics below namespace.

    published: (topic, type) pairs, as getPublishedTopics returns them, or a {topic: type}
    mapping (a bag's topic table). only: robot names to keep (empty keeps all).
    """
    pairs = published.items() if hasattr(published, 'items') else published
    keep = set(only)
    found = {}
    for topic, msg_type in pairs:
        if msg_type != POSE_TYPE:
            continue
        robot = robot_of_pose_topic(topic, namespace)
        if robot is not None and (not keep or robot in keep):
            found[topic] = robot
    return found
