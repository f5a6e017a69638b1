#!/usr/bin/env python3
"""The lesson's C++ move_robot as far as GO goes, for tests: `lesson_robot.py ID TEAM_SIZE`.

Like move_robot.cpp on the slides it publishes one ready status and then reads team_status
through a queue of one message, once a second (ros::spinOnce() in a 1 Hz loop): a message
that arrives after another, before the next spin, replaces it. It logs the lesson's lines
and, on GO, "Robot ID: Team is ready. Let's move!"; it drives nothing.

One difference, for the test's sake: after the lesson's 1 s sleep it also waits (at most
CONNECT_WAIT_S) until the monitor and its TEAM_SIZE - 1 teammates have been connected to its
publisher for STABLE_S without a break, so that its ready is not lost (the lesson's known
fragility: rospy, loaded, sometimes drops a new connection and makes it again a moment later)
and reaches every teammate: the case in which a GO sent too early is overtaken by a
teammate's ready.
"""
import sys
import threading
import time

import rospy
from course_common.rospy_internals import connection_ids

from multi_sync.msg import RobotStatus

CONNECT_WAIT_S = 40.0
STABLE_S = 1.0
SPIN_PERIOD_S = 1.0


class OneMessageQueue:
    """roscpp's subscriber queue of size 1: the newest message, taken by the next spin."""

    def __init__(self):
        self._lock = threading.Lock()
        self._msg = None

    def put(self, msg):
        with self._lock:
            self._msg = msg

    def take(self):
        with self._lock:
            msg, self._msg = self._msg, None
            return msg


def main():
    robot_id, team_size = int(sys.argv[1]), int(sys.argv[2])
    rospy.init_node('move_robot_%d' % robot_id)
    queue = OneMessageQueue()
    pub = rospy.Publisher('team_status', RobotStatus, queue_size=10)
    rospy.Subscriber('team_status', RobotStatus, queue.put, queue_size=1)
    time.sleep(1.0)  # the lesson's "wait for the publisher to connect"
    ns = rospy.get_namespace()
    listeners = {ns + 'monitor'} | {ns + 'move_robot_%d' % i for i in range(team_size)
                                    if i != robot_id}
    deadline = time.monotonic() + CONNECT_WAIT_S
    since = None
    while time.monotonic() < deadline:
        if listeners <= connection_ids(pub):
            since = since or time.monotonic()
            if time.monotonic() - since >= STABLE_S:
                break
        else:
            since = None
        time.sleep(0.01)
    ready = RobotStatus()
    ready.header.stamp = rospy.Time.now()
    ready.robot_id = robot_id
    ready.is_ready = True
    pub.publish(ready)
    rospy.loginfo('Robot %d published ready status', robot_id)
    while not rospy.is_shutdown():
        time.sleep(SPIN_PERIOD_S)
        msg = queue.take()
        if msg is not None and msg.header.frame_id == 'monitor':
            rospy.loginfo("Robot %d: Team is ready. Let's move!", robot_id)
            rospy.spin()
            return
        rospy.loginfo('Robot %d: waiting for team', robot_id)


if __name__ == '__main__':
    main()
