"""The stage_multi lesson's move_robot: one Stage robot straight ahead at 0.2 m/s."""
import threading

import rospy
from course_common.command_line import parse_argv_or_exit
from course_common.publishers import unqueued_publisher
from course_common.robot_ids import parse_robot_id
from course_common.rospy_internals import shutdown_requested
from course_common.startup import init_node, loop_at_rate
from geometry_msgs.msg import Twist

from stage_multi.drive import FORWARD_SPEED_MPS, RATE_HZ, cmd_vel_topic, node_name


class MoveRobotNode:
    """Drives one robot forward the whole time, as the lesson's move_robot.cpp.

    Subscribes: none (no laser, no odometry: Stage's collisions stop the robot at a wall,
        or at a teammate's back).
    Publishes:
        robot_<id>/cmd_vel (geometry_msgs/Twist): linear.x = 0.2 m/s, all else 0, at 10 Hz
            until shutdown; then one zero Twist. The lesson's queue is 10; here the publisher
            has no send queue (rospy's queue_size=None, course_common.publishers), so each
            message, the final stop included, is written before publish() returns: the stop
            leaves before the process exits.
    Services: none.
    Parameters: none. The robot id is argv[1] (0..19).
    """

    def __init__(self, robot_id):
        self.robot_id = robot_id
        self.topic = cmd_vel_topic(robot_id)
        self._forward = Twist()
        self._forward.linear.x = FORWARD_SPEED_MPS
        self._lock = threading.Lock()
        self._stopped = False
        self._pub = unqueued_publisher(self.topic, Twist)

    def cycle(self):
        """One turn of the lesson's while (ros::ok()) loop: the forward command."""
        with self._lock:
            if not self._stopped:
                self._pub.publish(self._forward)

    def drive(self):
        """The 10 Hz loop until shutdown. On sim time, a restarted stageros sends /clock back
        to 0.1 s and rospy's Rate gives up (ROSTimeMovedBackwardsException): the loop starts
        again, as the lesson's ros::Rate carries on."""
        while not shutdown_requested():
            loop_at_rate(RATE_HZ, self.cycle)

    def stop(self):
        """The zero Twist (rospy.on_shutdown: before rospy closes its connections).

        Under the lock, so that no forward command of the loop can follow it.
        """
        with self._lock:
            self._stopped = True
            self._pub.publish(Twist())


def main(argv=None):
    """rosrun stage_multi move_robot ROBOT_ID."""
    robot_id = parse_argv_or_exit(parse_robot_id, argv)
    init_node(node_name(robot_id))
    node = MoveRobotNode(robot_id)
    rospy.on_shutdown(node.stop)
    rospy.loginfo('Robot %d: moving forward at %.1f m/s on %s', robot_id, FORWARD_SPEED_MPS,
                  rospy.resolve_name(node.topic))
    # The loop runs beside the main thread: Ctrl-C runs the shutdown hook in the main thread,
    # which then waits for a cycle in progress instead of interrupting it.
    threading.Thread(target=node.drive, name='drive', daemon=True).start()
    rospy.spin()
