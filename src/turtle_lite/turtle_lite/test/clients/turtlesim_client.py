#!/usr/bin/env python3
"""A rospy client written for ROS 1 turtlesim, in the style of the ROS tutorials.

The course-commands test runs it unmodified against the workspace's turtlesim: it spawns a
turtle, gives it a red pen, teleports it (drawing a line) and echoes its pose.
"""
import sys

import rospy
from turtlesim.msg import Pose
from turtlesim.srv import SetPen, Spawn, TeleportAbsolute


def main():
    rospy.init_node('turtlesim_client')
    rospy.wait_for_service('spawn')
    spawn = rospy.ServiceProxy('spawn', Spawn)
    name = spawn(2.0, 2.0, 0.0, 'painter').name
    rospy.loginfo('spawned %s', name)

    set_pen = rospy.ServiceProxy(name + '/set_pen', SetPen)
    set_pen(255, 0, 0, 5, 0)
    teleport = rospy.ServiceProxy(name + '/teleport_absolute', TeleportAbsolute)
    teleport(2.0, 8.0, 1.57)

    # Echo the pose once the teleport shows, as `rostopic echo` would.
    for _ in range(100):
        pose = rospy.wait_for_message(name + '/pose', Pose, timeout=10.0)
        if abs(pose.y - 8.0) < 1e-3:
            print('pose x: %.2f y: %.2f theta: %.2f' % (pose.x, pose.y, pose.theta), flush=True)
            return 0
    return 1


if __name__ == '__main__':
    sys.exit(main())
