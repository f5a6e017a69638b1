"""Small rospy helpers shared by the nodes: the lesson's argv check, synchronous publishers."""
import sys
import warnings

import rospy


def parse_argv_or_exit(parse, argv=None):
    """Return parse(arguments after the program name, ROS remaps removed).

    On ValueError, log its message as an error (before init_node, as the lesson does: a bad
    argument needs no master) and exit with status 1.
    """
    args = rospy.myargv(sys.argv if argv is None else argv)[1:]
    try:
        return parse(args)
    except ValueError as err:
        rospy.logerr(str(err))
        sys.exit(1)


def synchronous_publisher(name, data_class, **kwargs):
    """A rospy Publisher without a send queue (queue_size=None).

    publish() then writes to every subscriber's socket from the calling thread before it
    returns: no hand-over to one sender thread per subscriber. Used where a message must
    leave at once (GO, the first command) or before the process exits (the final stop).
    rospy warns about a missing queue_size; here it is deliberate.
    """
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        return rospy.Publisher(name, data_class, queue_size=None, **kwargs)
