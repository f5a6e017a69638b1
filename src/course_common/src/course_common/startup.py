"""Node start-up shared by every node of the workspace: rospy.init_node and what it lacks."""
import rospy

from course_common.rospy_internals import cache_rosout_param


def init_node(name, **kwargs):
    """rospy.init_node(name, **kwargs), then one master call for rospy's /rosout parameter.

    Without it rospy asks the master for /rosout_disable_topics_generation on every log line
    while that parameter is unset, as under a plain roscore (see
    course_common.rospy_internals.cache_rosout_param). If the master cannot be asked (it
    went away), the node carries on as rospy would, one call per log line.
    """
    rospy.init_node(name, **kwargs)
    try:
        cache_rosout_param()
    except (OSError, rospy.ROSException) as err:
        rospy.logwarn('Could not read %s from the master (%s): each log line will ask it again',
                      '/rosout_disable_topics_generation', err)


def loop_at_rate(rate_hz, cycle):
    """Call cycle() at rate_hz until ROS shuts down: the slides' ``while (ros::ok())`` loop.

    Ctrl-C during the sleep (rospy's ROSInterruptException) is a normal exit, not an error.
    """
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        cycle()
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            return
