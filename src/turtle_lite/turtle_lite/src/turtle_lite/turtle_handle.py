"""A turtle's six ROS resources in turtlesim_node: two tick publishers, three services, cmd_vel."""
import rospy
from course_common.rospy_internals import tick_publisher
from geometry_msgs.msg import Twist
from turtlesim.msg import Color, Pose
from turtlesim.srv import SetPen, TeleportAbsolute, TeleportRelative


class TurtleHandle:
    """The six ROS resources of one turtle, created from already-resolved full names.

    ``sim`` provides the handlers: handle_set_pen, handle_teleport_relative,
    handle_teleport_absolute (each called with the turtle's name and the request) and
    handle_cmd_vel (name, Twist). pose_pub and color_pub are written by the tick
    (tick_publish), not with publish().
    """

    def __init__(self, sim, name, resources):
        self.name = name
        self.resources = resources
        self.pose_pub = self.color_pub = self.cmd_sub = None
        self.services = []
        try:
            self.pose_pub = tick_publisher(resources['pose'], Pose)
            self.color_pub = tick_publisher(resources['color_sensor'], Color)
            for key, srv_class, handler in (
                    ('set_pen', SetPen, sim.handle_set_pen),
                    ('teleport_relative', TeleportRelative, sim.handle_teleport_relative),
                    ('teleport_absolute', TeleportAbsolute, sim.handle_teleport_absolute)):
                self.services.append(rospy.Service(
                    resources[key], srv_class,
                    lambda req, handler=handler: handler(self.name, req)))
            # Subscribe last, once everything the callback touches exists.
            self.cmd_sub = rospy.Subscriber(resources['cmd_vel'], Twist,
                                            lambda msg: sim.handle_cmd_vel(self.name, msg),
                                            queue_size=1)
        except Exception:
            self.unregister()  # e.g. a service name already taken: leave nothing behind
            raise

    def unregister(self):
        """Remove all six resources from the master (turtlesim's NodeHandle going away)."""
        parts = [self.cmd_sub, self.pose_pub, self.color_pub]
        actions = [p.unregister for p in parts if p is not None]
        actions += [srv.shutdown for srv in self.services]
        for action in actions:
            try:
                action()
            except Exception as exc:
                rospy.logdebug('while unregistering turtle [%s]: %s', self.name, exc)
