#!/usr/bin/env python3
"""rostest node: on Stage, any start order works, and so does a robot restarted after GO.

Each case starts what it needs itself, as a student does in terminals (`rosrun stage_ros
stageros -g <world>`, `rosrun multi_sync move_robot_sync N`, `rosrun multi_sync monitor 4`),
on a simulator of its own, and stops it all at the end: the cases stand alone, in any order.
"""
import re
import sys
import unittest

import rospy
import rostest
from course_common.testing import info_texts, wait_for
from stage_watch import (
    AHEAD_OF,
    BACK,
    FRONT,
    MOVED_M,
    POSE_TOL_M,
    TEAM_SIZE,
    StageWatch,
    body_gap_m,
    laser_to_wall_m,
    lesson_line_kinds,
    on_sim_time,
    stall_runs,
    start_stageros,
)
from team_watch import NodeProcess

# Generous deadlines for a loaded 2-core machine (they cost time only on failure).
START_S = 60.0  # a rosrun'd node (or stageros) coming up, and what it waits for
EVENT_S = 30.0  # something that follows within a few simulated seconds
DRIVE_S = 120.0  # a drive of up to ~12 s of sim time at real time
STOP_DISTANCE_M = 0.5  # move_robot's default bumper distance, from the laser
MIN_GAP_M = 1.0  # move_robot's default teammate gap, between poses
KILL_AFTER_M = 0.2  # robot_0 is stopped this far into its drive: ~1.2 m short of its bumper
GAP_LINE = re.compile(r'^Robot 1: robot 0 is ([\d.]+) m ahead, waiting$')
INPUT_TIMEOUT_S = 2.0  # move_robot's default ~input_timeout_s: silent inputs stop a robot
# A bumper beyond turtlesim's 5.54 m half square, within Stage's 100 m (a laser's reach)
FAR_STOP_DISTANCE_M = 8.0


class TestStageStartOrder(unittest.TestCase):
    """Stage, the monitor and the robots started (and a robot restarted) in awkward orders."""

    def setUp(self):
        self._procs = {'robot': [], 'monitor': [], 'stage': []}
        self.watch = StageWatch()

    def tearDown(self):
        # Robots first (each sends its final stop to Stage), the simulator last.
        for kind in ('robot', 'monitor', 'stage'):
            for proc in self._procs[kind]:
                proc.stop()
        self.watch.close()

    def start_robot(self, i):
        robot = NodeProcess('move_robot_sync', str(i))
        self._procs['robot'].append(robot)
        return robot

    def start_monitor(self):
        monitor = NodeProcess('monitor', str(TEAM_SIZE))
        self._procs['monitor'].append(monitor)
        monitor.wait_line('Waiting for robots to connect...', START_S)
        return monitor

    def start_stage(self):
        stage = start_stageros(stop_timeout_s=EVENT_S)
        self._procs['stage'].append(stage)
        wait_for(self.watch.have_poses, START_S, "Stage's ground truth of every robot",
                 alive=stage.alive)
        return stage

    @staticmethod
    def without_sim_time():
        """Nodes started now stay on wall time, as nodes do that start before stageros sets
        /use_sim_time (stage_ros #49); an earlier case's stageros may have left it set."""
        if rospy.has_param('/use_sim_time'):
            rospy.delete_param('/use_sim_time')

    # --- the cases -----------------------------------------------------------------------
    def test_monitor_first_then_robots_one_by_one(self):
        watch = self.watch
        self.start_stage()
        monitor = self.start_monitor()
        robots = {}
        for i in watch.ids():
            robots[i] = self.start_robot(i)
            robots[i].wait_line('Robot %d published ready status' % i, START_S)
            if i == TEAM_SIZE - 1:
                break
            monitor.wait_line('Robot %d is ready!' % i, EVENT_S)
            # The team is not complete yet: no GO, and nobody moves.
            self.assertEqual(watch.gos(), [], monitor.tail())
            for j in robots:
                self.assertTrue(watch.still_since_first(j), 'robot_%d moved before GO' % j)
                self.assertEqual(watch.nonzero_cmds(j), [], 'robot_%d: motion before GO' % j)
        wait_for(watch.gos, EVENT_S, 'GO once the fourth robot is ready')
        wait_for(watch.moved, EVENT_S, 'every robot to drive off after GO')
        self.check_one_go(monitor, robots)

    def test_robots_before_stage(self):
        watch = self.watch
        self.without_sim_time()
        robots = {i: self.start_robot(i) for i in watch.ids()}
        for i, robot in robots.items():
            # move_robot_sync, the Stage lesson's robot, waits for Stage's topics only
            robot.wait_line('Robot %d: no pose yet on /robot_%d/base_pose_ground_truth'
                            % (i, i), START_S)
        for robot in robots.values():
            self.assertFalse(robot.printed('published ready status'), robot.tail())
        self.start_stage()
        for i, robot in robots.items():
            robot.wait_line('Robot %d published ready status' % i, START_S)
        monitor = self.start_monitor()
        wait_for(watch.gos, EVENT_S, "the monitor's GO")
        wait_for(watch.moved, EVENT_S, 'every robot to drive off after GO')
        self.check_one_go(monitor, robots)
        # Started before stageros, the robots stay on wall time; the monitor is on Stage's.
        for i, robot in robots.items():
            self.assertFalse(on_sim_time(robot.lines()), 'robot %d' % i)
        self.assertTrue(on_sim_time(monitor.lines()), 'the monitor')

    def test_robot_killed_and_restarted_after_go(self):
        watch = self.watch
        # The team on wall time (started before stageros); the restarted robot_0 will be on
        # Stage's clock: its positions' stamps go back, and its teammates must still use them.
        self.without_sim_time()
        robots = {i: self.start_robot(i) for i in watch.ids()}
        for i, robot in robots.items():
            robot.wait_line('Robot %d: MoveRobotConfig(' % i, START_S)  # its clock is chosen
        self.start_stage()
        for i, robot in robots.items():
            robot.wait_line('Robot %d published ready status' % i, START_S)
        monitor = self.start_monitor()
        wait_for(watch.gos, EVENT_S, "the monitor's GO")
        wait_for(lambda: watch.moved([0], KILL_AFTER_M), EVENT_S, 'robot_0 to drive off')

        # Ctrl-C while driving: robot_0 sends a final zero Twist, and Stage holds it there.
        first = robots[0]
        self.assertEqual(first.stop(), 0, first.tail())
        self.assertFalse(first.printed('stopping'), 'robot_0 stopped before the kill')
        wait_for(lambda: watch.last_cmd(0) == 0.0 and watch.odom_speed(0) == 0.0
                 and watch.standing(0), EVENT_S, "robot_0's final stop to reach Stage")
        x_dead = watch.x(0)
        # Its follower stops behind the last position robot_0 shared.
        wait_for(lambda: watch.stopped(1), DRIVE_S, 'robot_1 to stop behind the dead robot_0')
        waited = [GAP_LINE.match(t) for t in info_texts(robots[1].lines())]
        waited = [float(m.group(1)) for m in waited if m]
        self.assertEqual(len(waited), 1, robots[1].tail())
        self.assertLess(waited[0], MIN_GAP_M)
        x1 = watch.x(1)
        last_shared = [m.pose.x for m in watch.positions.messages() if m.robot_id == 0][-1]
        self.assertLess(last_shared - x1, MIN_GAP_M)
        self.assertGreater(body_gap_m(x_dead, x1), 0.0)
        stamps_before = watch.shared_stamps(0)

        # Restarted: it gets GO as it connects, with no new GO for the others.
        restarted = self.start_robot(0)
        robots[0] = restarted
        restarted.wait_line("Robot 0: Team is ready. Let's move!", START_S)
        wait_for(lambda: watch.x(0) > x_dead + MOVED_M, EVENT_S,
                 'the restarted robot_0 to drive on')
        wait_for(lambda: watch.x(1) > x1 + MOVED_M, EVENT_S, 'robot_1 to move on after it')
        robots[1].wait_line('Robot 1: path clear, moving on', EVENT_S)
        for i in watch.ids():
            wait_for(lambda i=i: watch.stopped(i), DRIVE_S, 'robot_%d to stop and stand' % i)

        # It may hear GO before its first pose, then it has no ready to publish.
        self.check_one_go(monitor, robots, patterns={0: '^(PW*)?TF$'})
        self.assertRegex(lesson_line_kinds(info_texts(first.lines()), 0), '^PW*TF$',
                         first.tail())
        self.check_stops()
        self.assertFalse(on_sim_time(first.lines()), 'robot_0 before the kill')
        self.assertTrue(on_sim_time(restarted.lines()), 'robot_0 restarted')
        stamps_after = watch.shared_stamps(0)[len(stamps_before):]
        self.assertTrue(stamps_after, 'no position of the restarted robot_0')
        self.assertLess(max(stamps_after), min(stamps_before), 'the stamps did not go back')

    def test_stage_killed_and_restarted_after_go(self):
        watch = self.watch
        self.without_sim_time()  # the robots on wall time: their ticks go on without /clock
        robots = {i: self.start_robot(i) for i in watch.ids()}
        for i, robot in robots.items():
            robot.wait_line('Robot %d: MoveRobotConfig(' % i, START_S)
        stage = self.start_stage()
        for i, robot in robots.items():
            robot.wait_line('Robot %d published ready status' % i, START_S)
        monitor = self.start_monitor()
        wait_for(watch.gos, EVENT_S, "the monitor's GO")
        wait_for(lambda: watch.moved(min_m=KILL_AFTER_M), EVENT_S, 'every robot to drive off')

        # Stage dies while the robots drive: with no scan to trust, each one stops and says why.
        self.assertEqual(stage.stop(), 0, stage.tail())
        # What the dead Stage sent: a stall is read from the new Stage's steps only (its
        # stamps start again from 0.1 s and would pair with the old ones).
        seen = [(len(watch.truth[i].messages()), len(watch.odom[i].messages()))
                for i in watch.ids()]
        last_stamp = max(watch.truth[i].latest().header.stamp for i in watch.ids())
        for i, robot in robots.items():
            robot.wait_line('Robot %d: nothing on /robot_%d/' % (i, i), EVENT_S)
            wait_for(lambda i=i: watch.last_cmd(i) == 0.0, EVENT_S,
                     'robot_%d to command a stop' % i)
        for robot in robots.values():
            line = [t for t in info_texts(robot.lines()) if 'nothing on' in t][0]
            self.assertTrue(line.endswith(', stopping'), line)
            # Silent for more than the timeout; printed to 0.1 s, so at least 2.0.
            age = float(re.search(r' for ([\d.]+) s', line).group(1))
            self.assertGreaterEqual(age, INPUT_TIMEOUT_S, line)

        # Stage again (its world from the start, its clock from 0.1 s): the robots hear it,
        # drive on from the start poses and stop by themselves, none stalled.
        self.start_stage()
        wait_for(lambda: all(watch.truth[i].latest().header.stamp < last_stamp
                             for i in watch.ids()), START_S, "the new Stage's ground truth")
        for i, robot in robots.items():
            robot.wait_line('Robot %d: path clear, moving on' % i, EVENT_S)
        for i in watch.ids():
            wait_for(lambda i=i: watch.moved([i]) and watch.stopped(i), DRIVE_S,
                     'robot_%d to drive on and stop again' % i)
        for i in watch.ids():
            truths = watch.truth[i].messages()[seen[i][0]:]
            odoms = watch.odom[i].messages()[seen[i][1]:]
            self.assertEqual(stall_runs(truths, odoms), [], 'robot_%d stalled' % i)
        self.check_stops(stalls=False)
        self.assertEqual(len(watch.gos()), 1, 'one GO: the robots never needed another')
        self.assertEqual(info_texts(monitor.lines()).count('All robots GO!'), 1, monitor.tail())

    def test_move_robot_takes_a_bumper_beyond_turtlesims_square(self):
        # move_robot (either simulator), not the lesson's move_robot_sync: its first pose
        # names Stage, which bounds the bumper by a laser's reach, not by turtlesim's 5.54 m.
        watch = self.watch
        self.start_stage()
        robot = NodeProcess('move_robot', '0', '_stop_distance_m:=%g' % FAR_STOP_DISTANCE_M,
                            '__name:=move_robot_far')
        self._procs['robot'].append(robot)
        robot.wait_line('Robot 0 published ready status', START_S)
        self.assertTrue(robot.printed('Robot 0: driven by Stage'), robot.tail())
        self.assertTrue(robot.printed('stop_distance_m=%.1f' % FAR_STOP_DISTANCE_M), robot.tail())
        monitor = NodeProcess('monitor', '1')
        self._procs['monitor'].append(monitor)
        line = robot.wait_line('Robot 0: laser: obstacle', EVENT_S)
        # The hall's wall, about 1.8 m ahead, is inside this bumper from the start (the
        # default 0.5 m would let the robot drive): no motion at all.
        ahead = float(line.split('obstacle ')[1].split(' m')[0])
        self.assertTrue(STOP_DISTANCE_M < ahead < FAR_STOP_DISTANCE_M, line)
        self.assertEqual(watch.nonzero_cmds(0), [], robot.tail())
        self.assertTrue(watch.still_since_first(0), 'robot_0 moved')
        self.assertTrue(robot.alive(), robot.tail())

    # --- shared checks -------------------------------------------------------------------
    def check_one_go(self, monitor, robots, patterns=None):
        """One GO on team_status, one "All robots GO!", one "Let's move!" per robot process:
        each robot's lesson lines in the lesson's order (patterns: robot id -> the regular
        expression its lesson_line_kinds must match instead of the lesson's)."""
        patterns = patterns or {}
        self.assertEqual(len(self.watch.gos()), 1, 'one GO, heard by every robot')
        wait_for(lambda: monitor.printed('All robots GO!'), EVENT_S, "the monitor's GO line")
        texts = info_texts(monitor.lines())
        self.assertEqual(texts.count('All robots GO!'), 1, monitor.tail())
        for i in self.watch.ids():
            self.assertEqual(texts.count('Robot %d is ready!' % i), 1, monitor.tail())
        for i, robot in robots.items():
            robot.wait_line('Robot %d: first move command' % i, EVENT_S)
            self.assertRegex(lesson_line_kinds(info_texts(robot.lines()), i),
                             patterns.get(i, '^PW*TF$'), robot.tail())

    def check_stops(self, stalls=True):
        """Every robot stopped by itself: the front pair short of the wall, the back pair
        behind its teammate, none ever stalled by Stage (stalls=False: checked by the case)."""
        watch = self.watch
        for i in watch.ids() if stalls else ():
            self.assertEqual(watch.stall_runs(i), [], 'robot_%d was stalled by Stage' % i)
        for i in FRONT:
            ahead = laser_to_wall_m(watch.x(i))
            self.assertTrue(0.0 < ahead <= STOP_DISTANCE_M + POSE_TOL_M,
                            'robot_%d: its laser %.3f m from the wall' % (i, ahead))
        for i in BACK:
            self.assertGreater(body_gap_m(watch.x(AHEAD_OF[i]), watch.x(i)), 0.0,
                               'robot_%d touches robot_%d' % (i, AHEAD_OF[i]))


if __name__ == '__main__':
    rospy.init_node('test_stage_start_order')
    rostest.rosrun('multi_sync', 'stage_start_order', TestStageStartOrder, sys.argv)
