"""turtle_lite's own rostest helpers: one simulator at the root namespace, its six resources.

Not a test itself. The helpers every package's tests share (recorders, the process runner,
master queries, turtle recorders, the teleop on a terminal) are in course_common.testing.
"""

import unittest

import rospy
from course_common.testing import START_DEADLINE_S, wait_for
from course_common.testing.master import names_under
from course_common.testing.recorders import LogRecorder
from std_srvs.srv import Empty
from turtle_lite.testing import ColorRecorder, PoseRecorder
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

DEFAULT_BG = (69, 86, 255)
DEFAULT_PEN = (179, 184, 255)

#: The six graph resources of one turtle, relative to its namespace (turtle.cpp).
TURTLE_TOPICS = ("cmd_vel", "pose", "color_sensor")
TURTLE_SERVICES = ("set_pen", "teleport_relative", "teleport_absolute")
TURTLE_RESOURCES = TURTLE_TOPICS + TURTLE_SERVICES


class SimTestCase(unittest.TestCase):
    """A TestCase against one turtlesim_node at the root namespace (the node is rospy's).

    setUpClass waits for the simulator's services and makes the proxies below; with
    RECORD_TURTLE1 (the default) it also records turtle1's pose, colour and the simulator's
    log, and waits for the first pose.
    """

    RECORD_TURTLE1 = True

    @classmethod
    def setUpClass(cls):
        for name in ('/clear', '/reset', '/spawn', '/kill'):
            rospy.wait_for_service(name, START_DEADLINE_S)
        cls.reset = rospy.ServiceProxy('/reset', Empty)
        cls.clear = rospy.ServiceProxy('/clear', Empty)
        cls.spawn = rospy.ServiceProxy('/spawn', Spawn)
        cls.kill = rospy.ServiceProxy('/kill', Kill)
        cls.set_pen = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
        cls.absolute = rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)
        cls.relative = rospy.ServiceProxy('/turtle1/teleport_relative', TeleportRelative)
        if cls.RECORD_TURTLE1:
            cls.pose = PoseRecorder()
            cls.color = ColorRecorder()
            cls.logs = LogRecorder('/turtlesim')
            wait_for(lambda: cls.pose.count() > 0, START_DEADLINE_S, 'the first pose')


def wait_connected(pub, what):
    """Wait until the publisher has a subscriber."""
    wait_for(lambda: pub.get_num_connections() > 0, START_DEADLINE_S, what)


def turtle_graph_names(namespace):
    """The full (topic set, service set) of the turtle whose namespace is ``namespace``."""
    return ({f"{namespace}/{t}" for t in TURTLE_TOPICS},
            {f"{namespace}/{s}" for s in TURTLE_SERVICES})


def has_turtle_at(namespace):
    """True when all six resources of a turtle are on the master under ``namespace``."""
    topics, svcs = turtle_graph_names(namespace)
    return names_under(namespace) >= topics | svcs
