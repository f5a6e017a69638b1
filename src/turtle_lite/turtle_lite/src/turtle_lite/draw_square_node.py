"""draw_square: reset the simulator, then drive turtle1 round a (drifting) square.

The node only: timer, topics, the reset call and main(). The state machine is the pure
SquareDriver of square_driver.
"""

import threading

import rospy
from course_common.startup import init_node, quiet_at_shutdown
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty
from turtlesim.msg import Pose

from turtle_lite.square_driver import SquareDriver

TICK_S = 0.016  # timer period, the simulator's tick


class DrawSquareNode:
    """Drives turtle1 round a square, as turtlesim's draw_square demo does.

    Subscribes:
        turtle1/pose (turtlesim/Pose, queue 1): the latest pose drives the state machine.
    Publishes:
        turtle1/cmd_vel (geometry_msgs/Twist, queue 1): 1 m/s forward, 0.4 rad/s turns,
            zero Twists while coming to rest; one zero Twist on shutdown.
    Services called:
        reset (std_srvs/Empty): once at start, without waiting for it, as turtlesim does;
            if no simulator answers, a warning is logged and the node carries on.
    Parameters: none.
    """

    def __init__(self):
        self._lock = threading.Lock()
        self._pose = None
        self._driver = SquareDriver()
        self._pub = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
        self._timer = None
        self._sub = None

    def reset_simulator(self):
        """Call reset once, without waiting for the service to appear."""
        try:
            rospy.ServiceProxy("reset", Empty)()
        except (rospy.ServiceException, rospy.ROSException) as err:
            # roscpp's call() just returns false here and turtlesim's draw_square ignores it.
            rospy.logwarn("draw_square: could not call %s (%s); continuing without reset",
                          rospy.resolve_name("reset"), err)

    def start(self):
        """Start the tick timer and the pose subscription (subscribe last)."""
        self._timer = rospy.Timer(rospy.Duration(TICK_S), quiet_at_shutdown(self._on_tick))
        self._sub = rospy.Subscriber("turtle1/pose", Pose, self._on_pose, queue_size=1)

    def stop(self):
        self._pub.publish(Twist())

    def _on_pose(self, msg):
        with self._lock:
            self._pose = msg

    def _on_tick(self, _event):
        with self._lock:
            pose = self._pose
            try:
                step = self._driver.step(pose)
            except ValueError as err:
                rospy.logwarn_throttle(1.0, "draw_square: ignoring bad pose: %s", err)
                return
        if step.reached:
            rospy.loginfo("Reached goal")
        if step.new_goal is not None:
            g = step.new_goal
            rospy.loginfo("New goal [%f %f, %f]", g.x, g.y, g.theta)
        if step.command is not None:
            twist = Twist()
            twist.linear.x, twist.angular.z = step.command
            self._pub.publish(twist)


def main():
    init_node("draw_square")
    node = DrawSquareNode()
    rospy.on_shutdown(node.stop)
    node.reset_simulator()
    node.start()
    rospy.spin()
