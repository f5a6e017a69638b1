#!/usr/bin/env python3
"""mimic with multisim.launch: turtlesim2's turtle follows turtlesim1's velocities."""

import threading
import unittest

import rospy
import rostest
from course_common.testing import START_DEADLINE_S, wait_for
from geometry_msgs.msg import Twist
from turtle_lite.testing import CENTER, PoseRecorder
from turtlesim.srv import TeleportAbsolute

DISTANCE_M = 0.5  # how far both turtles must have gone to count as moving
POSE_TOL = 1e-4
DRIVE_DEADLINE_S = 30.0


class Driver:
    """Publishes one Twist on the leader's cmd_vel at 20 Hz until stopped."""

    def __init__(self, linear, angular):
        self._pub = rospy.Publisher("/turtlesim1/turtle1/cmd_vel", Twist, queue_size=1)
        self._twist = Twist()
        self._twist.linear.x, self._twist.angular.z = linear, angular
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        rate = rospy.Rate(20)
        while not self._stop.is_set() and not rospy.is_shutdown():
            self._pub.publish(self._twist)
            rate.sleep()

    def stop(self):
        self._stop.set()
        self._thread.join()
        self._pub.unregister()


class MimicTest(unittest.TestCase):
    def setUp(self):
        self.leader = PoseRecorder("/turtlesim1/turtle1/pose")
        self.follower = PoseRecorder("/turtlesim2/turtle1/pose")
        self.addCleanup(self.leader.close)
        self.addCleanup(self.follower.close)
        wait_for(lambda: self.leader.latest() and self.follower.latest(), START_DEADLINE_S,
                 "poses from both simulators")
        # Each test starts from rest at the centre: wait out the 1 s cmd_vel timeout of the
        # previous test, then teleport both turtles home.
        for watcher, sim in ((self.leader, "turtlesim1"), (self.follower, "turtlesim2")):
            watcher.wait_latest(lambda p: p.linear_velocity == 0 and p.angular_velocity == 0,
                                "the turtle at rest")
            service = f"/{sim}/turtle1/teleport_absolute"
            rospy.wait_for_service(service, START_DEADLINE_S)
            rospy.ServiceProxy(service, TeleportAbsolute)(CENTER, CENTER, 0.0)
            watcher.wait_latest(lambda p: abs(p.x - CENTER) < POSE_TOL and abs(p.y - CENTER) <
                                POSE_TOL and p.theta == 0, "the turtle back at the centre")

    def drive(self, linear, angular):
        driver = Driver(linear, angular)
        self.addCleanup(driver.stop)
        return driver

    def test_reversing_leader_makes_follower_go_forward(self):
        start_leader = self.leader.latest()
        start_follower = self.follower.latest()
        self.drive(-1.5, 0.0)
        self.leader.wait_latest(lambda p: p.x < start_leader.x - DISTANCE_M,
                                "the leader reversing", DRIVE_DEADLINE_S)
        moved = self.follower.wait_latest(lambda p: p.x > start_follower.x + DISTANCE_M,
                                          "the follower moving forward", DRIVE_DEADLINE_S)
        # The follower copies the speed magnitude (1.5) and no turn: straight along +x.
        self.assertAlmostEqual(moved.linear_velocity, 1.5, delta=1e-6)
        self.assertAlmostEqual(moved.y, start_follower.y, delta=POSE_TOL)
        self.assertAlmostEqual(moved.theta, start_follower.theta, delta=POSE_TOL)

    def test_follower_turns_like_the_leader(self):
        start = self.follower.latest()
        self.drive(0.0, -1.0)
        turned = self.follower.wait_latest(lambda p: p.angular_velocity < -0.5,
                                           "the follower turning clockwise", DRIVE_DEADLINE_S)
        self.assertAlmostEqual(turned.angular_velocity, -1.0, delta=1e-6)
        self.assertAlmostEqual(turned.linear_velocity, 0.0, delta=1e-6)
        self.assertAlmostEqual(turned.x, start.x, delta=POSE_TOL)


if __name__ == "__main__":
    rospy.init_node("test_tools_mimic")
    rostest.rosrun("turtle_lite", "tools_mimic", MimicTest)
