"""move_robot's command, rate and names as the lesson has them (no rospy).

The lesson's move_robot publishes a constant Twist with linear.x = 0.2 on robot_<ID>/cmd_vel
at 10 Hz and reads nothing: a robot drives straight until Stage stalls it at a wall or a
teammate.
"""
from course_common.robot_ids import BAD_ROBOT_ID, valid_robot_id

FORWARD_SPEED_MPS = 0.2  # the lesson's msg.linear.x = 0.2, m/s along the robot's heading
RATE_HZ = 10.0  # the lesson's ros::Rate loop_rate(10)


def _checked(robot_id):
    if not valid_robot_id(robot_id):
        raise ValueError('%s, got %r' % (BAD_ROBOT_ID, robot_id))
    return robot_id


def node_name(robot_id):
    """The node's name, move_robot_<ID>, as the lesson's ros::init gives it."""
    return 'move_robot_%d' % _checked(robot_id)


def cmd_vel_topic(robot_id):
    """The robot's command topic, robot_<ID>/cmd_vel: relative, as the lesson's, so a
    namespace or a remap applies (stageros names its robots' topics /robot_<N>/...)."""
    return 'robot_%d/cmd_vel' % _checked(robot_id)
