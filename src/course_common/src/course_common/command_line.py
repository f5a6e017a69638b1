"""A node's command-line arguments (after the program name, ROS remaps removed), or exit 1."""
import sys

import rospy


def parse_argv_or_exit(parse, argv=None, label=None):
    """Return parse(the arguments after the program name, without ROS remaps).

    parse raises ValueError (or a subclass) with a message for the user; that message is
    logged as an error, prefixed with 'label: ' when a label is given, and the process exits
    with status 1. Call it before init_node, as the lessons do: a bad command line needs no
    master and registers no node.
    """
    args = rospy.myargv(sys.argv if argv is None else argv)[1:]
    try:
        return parse(args)
    except ValueError as err:
        rospy.logerr('%s: %s' % (label, err) if label else str(err))
        sys.exit(1)
