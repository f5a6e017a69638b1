#!/usr/bin/env python3
"""rostest node: a move_robot on sim time keeps commanding its robot when stageros restarts.

A restarted stageros sends /clock back to 0.1 s; rospy's Rate then gives up with
ROSTimeMovedBackwardsException. The lesson's C++ ros::Rate carries on, and so must move_robot:
else the robot stands still in the new world while its node seems alive.
"""
import unittest

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, spawn, wait_for
from course_common.testing.recorders import Recorder
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock

from stage_multi import lesson_world

STAGEROS = lesson_world.stageros_command('-g')
START_X = lesson_world.STARTS[0][0]  # robot_0's start
SPEED_MPS = 0.2
DRIVE_OFF_M = 0.1  # this far along +x: the robot is driving
BACK_M = 0.05  # within this of its start: a fresh world (the old one had it further on)


def _x(msg):
    return msg.pose.pose.position.x


class TestStageRestart(unittest.TestCase):
    """stageros, then move_robot 0 on sim time, then stageros stopped and started again."""

    def _stageros(self):
        stage = spawn(STAGEROS)
        self.addCleanup(stage.stop)
        return stage

    def test_robot_drives_on_after_stageros_restarts(self):
        clock = Recorder('/clock', Clock, keep=1)
        truth = Recorder('/robot_0/base_pose_ground_truth', Odometry)
        cmd = Recorder('/robot_0/cmd_vel', Twist)
        for rec in (clock, truth, cmd):
            self.addCleanup(rec.close)
        stage = self._stageros()
        wait_for(clock.latest, START_DEADLINE_S, 'the first /clock from stageros')
        self.assertIs(rospy.get_param('/use_sim_time'), True)
        # Started now, move_robot reads /use_sim_time true: its Rate runs on /clock.
        robot = spawn(['rosrun', 'stage_multi', 'move_robot', '0'])
        self.addCleanup(robot.stop)
        robot.wait_line('Robot 0: moving forward', START_DEADLINE_S)
        truth.wait_latest(lambda m: _x(m) > START_X + DRIVE_OFF_M, 'robot_0 driving',
                          START_DEADLINE_S)

        self.assertEqual(stage.stop(), 0, stage.output())
        stage = self._stageros()
        # Every ground truth from here on: the new world's first ones cannot be missed.
        truth.wait(lambda m: _x(m) < START_X + BACK_M, 'robot_0 back at its start in the new '
                   'world', START_DEADLINE_S)
        sent = cmd.count()
        truth.wait(lambda m: _x(m) > START_X + DRIVE_OFF_M,
                   'robot_0 driving again in the new world', EVENT_DEADLINE_S)
        self.assertGreater(cmd.count(), sent, 'commands after the restart')
        self.assertTrue(robot.alive(), robot.output())
        self.assertNotIn('Traceback', robot.output())
        forward = Twist()
        forward.linear.x = SPEED_MPS
        self.assertTrue(all(m == forward for m in cmd.messages()), 'only the forward command')


if __name__ == '__main__':
    rospy.init_node('test_stage_restart')
    rostest.rosrun('stage_multi', 'stage_restart', TestStageRestart)
