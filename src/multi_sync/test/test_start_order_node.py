#!/usr/bin/env python3
"""rostest node: no robot waits forever and no ready is lost, whatever the start order."""
import sys
import unittest

import rospy
import rostest
from course_common.rospy_internals import caller_id
from course_common.testing import wait_for
from course_common.testing.master import LostSubscriber
from team_watch import NodeProcess, TeamWatch

from multi_sync.msg import RobotStatus

# Generous deadlines for a loaded 2-core machine; passing tests finish far sooner.
START_S = 60.0
EVENT_S = 30.0
# The monitor's line for a ready report after GO (it does not send GO again).
LATE_READY = 'Robot %d reported ready after GO'
# The WARN of a node that registered its team_status publisher again for a lost subscriber.
HEALED = '%s: /lost_listener subscribe to /team_status but never connected: registered it again'


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
            self.assertTrue(robot.printed('Robot %d published ready status' % i), robot.lines())
        self.assertEqual(watch.go_count(), 1)
        self.assertNotIn(4, watch.first_move_wall)

        # 2. Monitor restarted after GO: it collects the (moving) robots again and says GO.
        self.assertEqual(monitor.stop(), 0, monitor.lines())
        monitor = self.start('monitor', '4')
        wait_for(lambda: monitor.printed('All robots GO!'), EVENT_S,
                 'the restarted monitor to count the team again')
        for i in range(4):
            self.assertTrue(monitor.printed('Robot %d is ready!' % i), monitor.lines())

        # 3. A robot started after GO does not wait for a team that is already gone.
        self.start('move_robot', '4')
        wait_for(lambda: watch.moved([4]), EVENT_S, 'robot 4, started after GO, to move')

        # 4. A robot stopped with Ctrl-C sends a stop; restarted, it moves again.
        self.assertEqual(robots[2].stop(), 0, robots[2].lines())
        wait_for(lambda: watch.last_cmd.get(2) == 0.0, EVENT_S, 'the stop command of robot 2')
        with watch.lock:
            del watch.first_move_wall[2]
        self.start('move_robot', '2')
        wait_for(lambda: watch.moved([2]), EVENT_S, 'robot 2, restarted after GO, to move')

        # The monitor survived all of it.
        self.assertIsNone(monitor.returncode, monitor.lines())
        watch.close()

    def test_move_robot_refuses_on_turtlesim_what_fits_stage_only(self):
        # move_robot takes either simulator: a bumper of 8 m fits Stage (a laser's reach) but
        # not turtlesim's 11.09 m square. The first pose names turtlesim: FATAL, exit 1.
        watch = TeamWatch(5)
        self.addCleanup(watch.close)
        wait_for(watch.have_poses, START_S, 'the five turtles')
        cases = (('_stop_distance_m:=8',
                  'parameter ~stop_distance_m = 8.0: expected a finite number in [0, 5.54444]'),
                 ('_world_size_m:=0.5', 'parameters ~stop_distance_m and ~world_size_m'))
        for k, (param, text) in enumerate(cases):
            with self.subTest(param=param):
                # A node name of its own per case: private parameters stay on the master.
                robot = self.start('move_robot', '1', param, '__name:=refused_%d' % k)
                code = robot.wait_exit(START_S)
                output = robot.output()
                self.assertEqual(code, 1, output)
                self.assertIn('Robot 1: driven by turtlesim', output)
                fatal = [line for line in output.splitlines() if '[FATAL]' in line]
                self.assertEqual(len(fatal), 1, output)
                self.assertIn('move_robot: %s' % text, fatal[0])
                self.assertIn('(on turtlesim)', fatal[0])
                self.assertNotIn('published ready status', output)
                self.assertNotIn('Traceback', output)
        self.assertEqual(watch.ready_counts.get(1, 0), 0, 'a refused robot announced ready')

    def test_one_go_for_a_subscriber_connecting_as_go_goes_out(self):
        # The flake "2 != 1 : one GO" made deterministic. This test node is robot 0 of a team
        # of one in /race: it reports ready before it subscribes, so the monitor's GO waits
        # for its subscription and goes out as it connects (from the monitor's subscribe
        # listener); then it re-announces, as a robot's timer does, after GO. Before the fix
        # the monitor's latched GO reached this subscriber twice (rospy sends the latch after
        # the listeners), or, when the GO was forced by the 3 s deadline first, the
        # re-announcement was answered with a second GO.
        gos = []
        pub = rospy.Publisher('/race/team_status', RobotStatus, queue_size=10)
        monitor = self.start('monitor', '1', env={'ROS_NAMESPACE': 'race'})
        wait_for(lambda: pub.get_num_connections() >= 1, START_S,
                 'the monitor to subscribe to /race/team_status')
        pub.publish(status(0))
        wait_for(lambda: monitor.printed('Robot 0 is ready!'), EVENT_S, 'robot 0 counted')
        pub.publish(status(0))  # re-announced while GO waits for this node: not "after GO"
        sub = rospy.Subscriber('/race/team_status', RobotStatus,
                               lambda m: m.header.frame_id == 'monitor' and gos.append(m),
                               queue_size=10, tcp_nodelay=True)
        try:
            wait_for(lambda: gos, EVENT_S, 'GO once this node subscribed')
            pub.publish(status(0))
            wait_for(lambda: monitor.printed(LATE_READY % 0) or len(gos) > 1, EVENT_S,
                     'the monitor to handle the re-announcement after GO')
            self.assertEqual(len(gos), 1, 'one GO, heard by every robot')
            go_line = monitor.wait_line('All robots GO!', EVENT_S)
            lines = monitor.lines()
            self.assertEqual([line for line in lines[:lines.index(go_line)]
                              if LATE_READY % 0 in line], [], lines)
        finally:
            sub.unregister()
            pub.unregister()
        self.assertEqual(monitor.stop(), 0, monitor.lines())

    def test_lost_team_status_subscribers_get_the_publishers_again(self):
        # A subscriber the master lists on team_status that never connected (a connection
        # lost on a loaded machine) would never hear the robot's ready, or the monitor's GO:
        # both register their publisher again, and the master tells it once more.
        watch = TeamWatch(5)
        wait_for(watch.have_poses, START_S, 'the five turtles')
        robot = self.start('move_robot', '3')
        monitor = self.start('monitor', '5')  # one robot of five: no GO, robot 3 keeps waiting
        wait_for(lambda: monitor.printed('Robot 3 is ready!'), START_S, 'robot 3 counted')
        with LostSubscriber('/lost_listener', '/team_status', 'multi_sync/RobotStatus'):
            for proc, who in ((robot, 'Robot 3'), (monitor, 'monitor')):
                proc.wait_line(HEALED % who, EVENT_S)
        self.assertFalse(monitor.printed('All robots GO!'), monitor.lines())
        for proc, who in ((robot, 'Robot 3'), (monitor, 'monitor')):
            # Connected subscribers (this test, the robot, the monitor) are never named.
            self.assertEqual([line for line in proc.lines_with('never connected')
                              if HEALED % who not in line], [], proc.lines())

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
        self.assertEqual(sum('is ready!' in line for line in monitor.lines()), 1,
                         monitor.lines())
        self.assertFalse(monitor.printed('All robots GO!'), monitor.lines())

        # The watch also heard the fake GO above (this node's own message): count the
        # monitor's only.
        def monitor_gos():
            with watch.lock:
                return [m for _, m in watch.go_msgs if caller_id(m) == '/bad/monitor']

        pub.publish(status(0))
        wait_for(monitor_gos, EVENT_S, 'GO once robots 0 and 1 are ready')
        wait_for(lambda: monitor.printed('All robots GO!'), EVENT_S, 'the GO log line')
        # A ready after GO is recorded, not answered: every subscriber has its one GO.
        pub.publish(status(1))
        wait_for(lambda: monitor.printed(LATE_READY % 1), EVENT_S, 'the late ready logged')
        self.assertEqual(len(monitor_gos()), 1, 'GO sent again after a late ready')
        self.assertIsNone(monitor.returncode, monitor.lines())
        self.assertEqual(monitor.stop(), 0, monitor.lines())
        pub.unregister()
        watch.close()


if __name__ == '__main__':
    rospy.init_node('test_start_order')
    rostest.rosrun('multi_sync', 'start_order', TestStartOrder, sys.argv)
