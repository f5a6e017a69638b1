"""move_turtle's command line: which robot to drive and its topics (pure, no rospy)."""
from course_common.graph_names import graph_name_error

DEFAULT_ROBOT = 'turtle1'  # the slides' first version drives turtle1 and takes no argument
USAGE = 'usage: rosrun my_turtle move_turtle [ROBOT_NAME]   (default turtle1; e.g. turtle2)'


class UsageError(ValueError):
    """The command line is wrong; the message says what was expected."""


def robot_from_args(args):
    """The robot name from the arguments after the program name (ROS remaps removed).

    No argument: turtle1, as the slides' first version. One argument: that robot, which must be
    a valid ROS graph name (roscpp's rule, as ros::NodeHandle would enforce in the slide's C++).
    Raises UsageError otherwise.
    """
    if not args:
        return DEFAULT_ROBOT
    if len(args) > 1:
        raise UsageError('expected at most one robot name, got %d arguments %r. %s'
                         % (len(args), list(args), USAGE))
    name = args[0]
    if not name:
        raise UsageError('the robot name is empty. %s' % USAGE)
    if name.startswith('~'):
        raise UsageError('the robot name %r is private (~); expected a robot such as turtle2. %s'
                         % (name, USAGE))
    if name.endswith('/'):
        raise UsageError('the robot name %r ends with "/"; expected a robot such as turtle2. %s'
                         % (name, USAGE))
    error = graph_name_error(name)
    if error is not None:
        raise UsageError('the robot name %r is not a valid ROS name: %s %s'
                         % (name, error, USAGE))
    return name


def robot_topics(robot):
    """(cmd_vel topic, pose topic) of a robot, relative like the slide's robot_name + "/..."."""
    return robot + '/cmd_vel', robot + '/pose'
