"""Node start-up shared by every node of the workspace: rospy.init_node and what it lacks,
and the loops and callbacks that publish until ROS shuts down under them."""
import functools

import rospy

from course_common.rospy_internals import (
    cache_rosout_param,
    deep_tcpros_backlog,
    keep_every_publisher_update,
    shut_down_off_the_signal,
    shutdown_requested,
)


def init_node(name, **kwargs):
    """rospy.init_node(name, **kwargs), its Ctrl-C made safe, every subscriber and every
    publisher the master names connected, one master call for /rosout's param.

    rospy's SIGINT/SIGTERM handler shuts the node down inside whatever the signal interrupted,
    which can fail (a "Logging error" traceback at Ctrl-C) or hang; the node's shutdown runs
    in a thread instead (course_common.rospy_internals.shut_down_off_the_signal).

    A rospy node refuses subscribers beyond five connecting at once, and can drop a
    publisher the master names to a subscription registering at the same time as that
    publisher; either way that subscription never connects. Here neither happens
    (course_common.rospy_internals.deep_tcpros_backlog, keep_every_publisher_update).

    Without the master call, rospy asks the master for /rosout_disable_topics_generation on
    every log line while that parameter is unset, as under a plain roscore (see
    course_common.rospy_internals.cache_rosout_param). If the master cannot be asked (it
    went away), the node carries on as rospy would, one call per log line.
    """
    deep_tcpros_backlog()
    keep_every_publisher_update()
    rospy.init_node(name, **kwargs)
    shut_down_off_the_signal()
    try:
        cache_rosout_param()
    except (OSError, rospy.ROSException) as err:
        rospy.logwarn('Could not read %s from the master (%s): each log line will ask it again',
                      '/rosout_disable_topics_generation', err)


def quiet_at_shutdown(callback):
    """callback, made to return None quietly when ROS shuts down under it.

    rospy closes every topic before rospy.is_shutdown() turns true: a publish in between (a
    node of the same name took over, Ctrl-C, rosnode kill) raises "publish() to a closed
    topic". A rospy.ROSException from callback while ROS is shutting down is that race, not
    an error; at any other time it is raised as before. For loops' bodies, rospy.Timer
    callbacks and threads that publish.
    """
    @functools.wraps(callback)
    def guarded(*args, **kwargs):
        try:
            return callback(*args, **kwargs)
        except rospy.ROSException:
            if shutdown_requested():
                return None
            raise
    return guarded


def loop_at_rate(rate_hz, cycle):
    """Call cycle() at rate_hz until ROS shuts down: the slides' ``while (ros::ok())`` loop.

    It ends quietly when ROS shuts down, wherever that lands: Ctrl-C during the sleep
    (rospy's ROSInterruptException), or shutdown between the check and a publish in cycle
    (quiet_at_shutdown).
    """
    rate = rospy.Rate(rate_hz)
    cycle = quiet_at_shutdown(cycle)
    while not shutdown_requested():
        cycle()
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            return
