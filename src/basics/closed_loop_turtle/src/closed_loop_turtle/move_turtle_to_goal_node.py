"""ROS node of Lab 2 task two: drive the Pioneer to a goal pose (move_turtle_to_goal.py)."""
import contextlib
import threading

import rospy
from course_common.param_loader import load_or_exit
from course_common.planar import Pose
from course_common.startup import init_node, quiet_at_shutdown
from geometry_msgs.msg import Pose2D, Twist

from closed_loop_turtle.go_to_goal import GoalError, Phase, check_goal, check_pose, step
from closed_loop_turtle.move_turtle_to_goal_params import load_config

QUEUE_SIZE = 10  # the lab's command queue
POSE_LOG_PERIOD_S = 1.0  # the lab logs every pose; at 62.5 Hz that floods the screen
WARN_PERIOD_S = 5.0  # throttle for repeated warnings (bad poses, no pose yet)


def _pose(msg):
    return Pose(float(msg.x), float(msg.y), float(msg.theta))


class MoveTurtleToGoalNode:
    """Drives the Pioneer to each goal pose with the lab's two-phase law (go_to_goal.step).

    Unlike the lab, the control runs in a timer at ~rate_hz, so poses and goals are taken in
    while the robot drives: a new goal replaces the current one at once. Commands go out only
    while a goal is active (the teleop can drive the robot otherwise), then one zero Twist.
    Logs the lab's "Reach position" and "Reach orientation"; publishes the goal reached.
    Goals with a non-finite field or outside the world are refused with a warning (the current
    goal, if any, carries on); poses with a non-finite field are ignored (throttled warning).

    Subscribes:
        /pioneer/pose (geometry_msgs/Pose2D, queue 1): the robot's pose.
        /pioneer/goal (geometry_msgs/Pose2D, queue 10): the goal pose (x, y in m, theta in rad).
    Publishes:
        /pioneer/cmd_vel (geometry_msgs/Twist, queue 10): the command, at ~rate_hz while a goal
            is active; one zero Twist on arrival and at shutdown.
        /pioneer/goal_reached (geometry_msgs/Pose2D, latched): each goal once it is reached.
    Services: none.
    Parameters:
        ~k_rho (float, default 3.14, 1/s), ~k_alpha (5.0, 1/s), ~k_beta (-3.0, 1/s): the lab's
            gains; k_rho > 0, k_beta < 0, k_alpha > k_rho.
        ~position_tolerance (float, default 0.1, m), ~heading_tolerance (0.05, rad).
        ~max_linear_mps (float, default 1.2), ~max_angular_radps (5.236): top speeds.
        ~rate_hz (float, default 100): control rate.
        ~world_size_m (float, default 11.088889): goals must lie in [0, size] on both axes.
    The topic names are the lab's absolute ones; remaps apply.
    """

    def __init__(self, config):
        self._config = config
        self._lock = threading.Lock()
        self._pose = None
        self._goal = None
        self._phase = Phase.ARRIVED
        self._cmd_pub = rospy.Publisher('/pioneer/cmd_vel', Twist, queue_size=QUEUE_SIZE)
        self._reached_pub = rospy.Publisher('/pioneer/goal_reached', Pose2D, queue_size=1,
                                            latch=True)
        self._timer = rospy.Timer(rospy.Duration(1.0 / config.rate_hz),
                                  quiet_at_shutdown(self._on_tick))
        # Subscribe last: the callbacks use the lock and the state above.
        self._pose_sub = rospy.Subscriber('/pioneer/pose', Pose2D, self._on_pose, queue_size=1)
        self._goal_sub = rospy.Subscriber('/pioneer/goal', Pose2D, self._on_goal,
                                          queue_size=QUEUE_SIZE)

    def _on_pose(self, msg):
        try:
            pose = check_pose(_pose(msg))
        except GoalError as err:
            rospy.logwarn_throttle(WARN_PERIOD_S, 'move_turtle_to_goal: ignoring %s' % err)
            return
        with self._lock:
            self._pose = pose
        # The lab's line (its format has no theta placeholder, so theta is not shown).
        rospy.loginfo_throttle(POSE_LOG_PERIOD_S, f'I heard ({pose.x:2f}, {pose.y:2f})')

    def _on_goal(self, msg):
        try:
            goal = check_goal(_pose(msg), self._config.world_size_m)
        except GoalError as err:
            rospy.logwarn('move_turtle_to_goal: refusing %s; nothing sent' % err)
            return
        with self._lock:
            replaced = self._goal if self._phase is not Phase.ARRIVED else None
            self._goal = goal
            self._phase = Phase.POSITION
        if replaced is not None:
            rospy.loginfo('move_turtle_to_goal: new goal (%.3f, %.3f, %.3f) replaces (%.3f, %.3f, '
                          '%.3f)', goal.x, goal.y, goal.theta, replaced.x, replaced.y,
                          replaced.theta)
        else:
            rospy.loginfo('move_turtle_to_goal: new goal (%.3f, %.3f, %.3f)',
                          goal.x, goal.y, goal.theta)

    def _on_tick(self, _event):
        with self._lock:
            if self._phase is Phase.ARRIVED:
                return
            if self._pose is None:
                rospy.logwarn_throttle(WARN_PERIOD_S, 'move_turtle_to_goal: waiting for a pose '
                                       'on %s' % rospy.resolve_name('/pioneer/pose'))
                return
            goal = self._goal
            result = step(self._phase, self._pose, goal, self._config.gains,
                          self._config.tolerances, self._config.limits)
            self._phase = result.phase
            # Published under the lock, so a goal arriving now cannot be overtaken by this
            # step's command for the old one.
            self._publish(result.command.linear_mps, result.command.angular_radps)
        if result.reached_position:
            rospy.loginfo('Reach position')
        if result.reached_orientation:
            rospy.loginfo('Reach orientation')
            with contextlib.suppress(rospy.ROSException, ValueError):
                self._reached_pub.publish(Pose2D(x=goal.x, y=goal.y, theta=goal.theta))

    def _publish(self, linear_mps, angular_radps):
        twist = Twist()
        twist.linear.x = linear_mps
        twist.angular.z = angular_radps
        # A tick racing shutdown finds the publisher closed: nothing left to drive.
        with contextlib.suppress(rospy.ROSException, ValueError):
            self._cmd_pub.publish(twist)

    def stop(self):
        """Stops the timer and sends one zero Twist (rospy.on_shutdown)."""
        self._timer.shutdown()
        with self._lock:
            self._phase = Phase.ARRIVED
            self._publish(0.0, 0.0)


def main():
    """Entry point of move_turtle_to_goal.py."""
    # anonymous=True as in the lab's controller_init ('turtle_closed_loop').
    init_node('turtle_closed_loop', anonymous=True)
    config = load_or_exit(load_config, 'move_turtle_to_goal')
    rospy.loginfo('move_turtle_to_goal: k_rho=%g k_alpha=%g k_beta=%g position_tolerance=%g m '
                  'heading_tolerance=%g rad max_linear=%g m/s max_angular=%g rad/s rate=%g Hz '
                  'world=%g m', config.gains.k_rho, config.gains.k_alpha, config.gains.k_beta,
                  config.tolerances.position_m, config.tolerances.heading_rad,
                  config.limits.max_linear_mps, config.limits.max_angular_radps, config.rate_hz,
                  config.world_size_m)
    node = MoveTurtleToGoalNode(config)
    rospy.on_shutdown(node.stop)
    rospy.spin()
