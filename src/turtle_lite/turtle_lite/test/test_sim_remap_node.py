#!/usr/bin/env python3
"""<remap from="/turtle1" to="/robot1"/> moves all of turtle1."""

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, wait_for
from course_common.testing.master import names_under
from geometry_msgs.msg import Twist
from sim_support import TURTLE_RESOURCES, SimTestCase, wait_connected
from turtle_lite.testing import CENTER, POSE_TOL, PoseRecorder
from turtlesim.srv import TeleportAbsolute


class SimRemapTest(SimTestCase):
    # turtle1 lives under /robot1 here: recording /turtle1/* would put it on the master.
    RECORD_TURTLE1 = False

    def test_namespace_remap_keeps_the_turtle_name(self):
        wait_for(lambda: len(names_under('/robot1')) == 6, START_DEADLINE_S,
                 'six resources under /robot1')
        self.assertEqual(names_under('/robot1'), {'/robot1/' + r for r in TURTLE_RESOURCES})
        self.assertEqual(names_under('/turtle1'), set())

        pose = PoseRecorder('/robot1/pose')
        pub = rospy.Publisher('/robot1/cmd_vel', Twist, queue_size=1)
        wait_connected(pub, '/robot1/cmd_vel')
        msg = Twist()
        msg.angular.z = 1.0
        pub.publish(msg)
        pose.wait(lambda p: p.angular_velocity == 1.0, 'a command through /robot1/cmd_vel')
        rospy.ServiceProxy('/robot1/teleport_absolute', TeleportAbsolute)(2.0, 3.0, 0.0)
        pose.wait(lambda p: abs(p.x - 2.0) < POSE_TOL, 'a teleport through /robot1')

        # The turtle is still named turtle1.
        with self.assertRaises(rospy.ServiceException):
            self.kill('robot1')
        self.assertEqual(self.spawn(1, 1, 0, '').name, 'turtle2')
        wait_for(lambda: len(names_under('/turtle2')) == 6, EVENT_DEADLINE_S, '/turtle2')

        # After a reset turtle1 lands on /robot1 again; turtle2 is gone.
        self.reset()
        wait_for(lambda: not names_under('/turtle2'), EVENT_DEADLINE_S, '/turtle2 to go')
        pose.wait(lambda p: abs(p.x - CENTER) < POSE_TOL, 'turtle1 respawned on /robot1')
        self.assertEqual(len(names_under('/robot1')), 6)
        self.assertEqual(names_under('/turtle1'), set())

        # Our own publisher and subscriber keep their topics on the master: drop them first.
        pub.unregister()
        pose.close()
        self.kill('turtle1')
        wait_for(lambda: not names_under('/robot1'), EVENT_DEADLINE_S, '/robot1 to go')


if __name__ == '__main__':
    rospy.init_node('test_sim_remap')
    rostest.rosrun('turtle_lite', 'sim_remap', SimRemapTest)
