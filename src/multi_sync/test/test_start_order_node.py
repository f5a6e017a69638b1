#!/usr/bin/env python3
"""rostest node: no robot waits forever and no ready is lost, whatever the start order."""
import sys
import unittest

import rospy
import rostest
from course_common.testing import wait_for
from team_watch import NodeProcess, TeamWatch

from multi_sync.msg import RobotStatus

# Generous deadlines for a loaded 2-core machine; passing tests finish far sooner.
START_S = 60.0
EVENT_S = 30.0


def status(robot_id, is_ready=True, frame_id=''):
    msg = RobotStatus()
    msg.header.stamp = rospy.Time.now()
    msg.header.frame_id = frame_id
    msg.robot_id = robot_id
    msg.is_ready = is_ready
    return msg


class TestStartOrder(unittest.TestCase):
    """Starts and stops monitor and robots (rosrun, as students do) in awkward orders."""

    def setUp(self):
        self.procs = []

    def tearDown(self):
        for proc in reversed(self.procs):
            proc.stop()

    def start(self, *args, env=None):
        proc = NodeProcess(*args, env=env)
        self.procs.append(proc)
        return proc

    def test_monitor_first_restarts_and_late_robots(self):
        watch = TeamWatch(5)
        wait_for(watch.have_poses, START_S, 'the five turtles')

        # 1. Monitor first, then the robots one by one.
        monitor = self.start('monitor', '4')
        wait_for(lambda: monitor.printed('Waiting for robots to connect...'), START_S,
                 'the monitor to start')
        robots = {i: self.start('move_robot', str(i)) for i in range(4)}
        wait_for(watch.go_count, START_S, 'GO after the four robots are ready')
        wait_for(lambda: watch.moved(range(4)), EVENT_S, 'robots 0..3 to move')
        for i, robot in robots.items():
            self.assertTrue(robot.printed('Robot %d published ready status' % i), robot.output)
        self.assertEqual(watch.go_count(), 1)
        self.assertNotIn(4, watch.first_move_wall)

        # 2. Monitor restarted after GO: it collects the (moving) robots again and says GO.
        self.assertEqual(monitor.stop(), 0, monitor.output)
        monitor = self.start('monitor', '4')
        wait_for(lambda: monitor.printed('All robots GO!'), EVENT_S,
                 'the restarted monitor to count the team again')
        for i in range(4):
            self.assertTrue(monitor.printed('Robot %d is ready!' % i), monitor.output)

        # 3. A robot started after GO does not wait for a team that is already gone.
        self.start('move_robot', '4')
        wait_for(lambda: watch.moved([4]), EVENT_S, 'robot 4, started after GO, to move')

        # 4. A robot stopped with Ctrl-C sends a stop; restarted, it moves again.
        self.assertEqual(robots[2].stop(), 0, robots[2].output)
        wait_for(lambda: watch.last_cmd.get(2) == 0.0, EVENT_S, 'the stop command of robot 2')
        with watch.lock:
            del watch.first_move_wall[2]
        self.start('move_robot', '2')
        wait_for(lambda: watch.moved([2]), EVENT_S, 'robot 2, restarted after GO, to move')

        # The monitor survived all of it.
        self.assertIsNone(monitor.proc.poll(), monitor.output)
        watch.close()

    def test_monitor_ignores_bad_statuses(self):
        # A monitor of two in its own namespace, fed by hand on /bad/team_status.
        watch = TeamWatch(0, namespace='/bad')
        pub = rospy.Publisher('/bad/team_status', RobotStatus, queue_size=100)
        monitor = self.start('monitor', '2', env={'ROS_NAMESPACE': 'bad'})
        wait_for(lambda: pub.get_num_connections() >= 2, START_S,
                 'the monitor to subscribe to /bad/team_status')
        for msg in (status(-1, frame_id='monitor'),   # a GO from another monitor
                    status(25), status(-1), status(20),  # ids outside 0..19
                    status(0, is_ready=False),          # not ready
                    status(1), status(1), status(1)):   # one robot, three times
            pub.publish(msg)
        wait_for(lambda: monitor.printed('Robot 1 is ready!'), EVENT_S, 'robot 1 counted')
        wait_for(lambda: monitor.printed('Ignoring status with robot_id 25'), EVENT_S,
                 'a warning about id 25')
        self.assertEqual(sum('is ready!' in line for line in monitor.output), 1,
                         monitor.output)
        self.assertFalse(monitor.printed('All robots GO!'), monitor.output)

        pub.publish(status(0))
        wait_for(watch.go_count, EVENT_S, 'GO once robots 0 and 1 are ready')
        wait_for(lambda: monitor.printed('All robots GO!'), EVENT_S, 'the GO log line')
        # A ready after GO (a robot that missed it) is answered with GO again.
        pub.publish(status(1))
        wait_for(lambda: watch.go_count() >= 2, EVENT_S, 'GO sent again after a late ready')
        self.assertIsNone(monitor.proc.poll(), monitor.output)
        self.assertEqual(monitor.stop(), 0, monitor.output)
        pub.unregister()
        watch.close()


if __name__ == '__main__':
    rospy.init_node('test_start_order')
    rostest.rosrun('multi_sync', 'start_order', TestStartOrder, sys.argv)
