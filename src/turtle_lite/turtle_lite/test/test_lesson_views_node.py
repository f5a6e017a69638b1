#!/usr/bin/env python3
"""pose_to_tf, lesson_markers and the simulator's rviz view on running simulators."""

import os
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest
from course_common.rviz.screen import error_lines
from course_common.rviz.snapshot import RvizOnXvfb
from course_common.testing import START_DEADLINE_S, results_dir, spawn, wait_for
from course_common.testing.master import subscribers_of
from course_common.testing.views import TfPoseCheck
from turtle_lite.testing import POSE_TOL, WORLD
from turtlesim.msg import Pose
from turtlesim.srv import Kill, Spawn, TeleportAbsolute
from visualization_msgs.msg import Marker, MarkerArray

EVENT_DEADLINE_S = 20.0  # discovery (0.5 s), a pose, a marker tick (0.2 s) on a loaded machine
TOOL_DEADLINE_S = 60.0  # tf_echo / view_frames.py: rosrun plus their own 5 s of listening



class LessonViewsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lesson_views')
        cls.markers = None
        cls.sub = rospy.Subscriber('/lesson_markers', MarkerArray, cls._on_markers, queue_size=1)
        rospy.wait_for_service('/spawn', START_DEADLINE_S)
        rospy.wait_for_service('/sim2/spawn', START_DEADLINE_S)

    @classmethod
    def _on_markers(cls, msg):
        cls.markers = msg

    def marker(self, ns, text=None):
        msg = self.markers
        if msg is None:
            return None
        for m in msg.markers:
            if m.ns == ns and m.action == Marker.ADD and (text is None or m.text == text):
                return m
        return None

    def test_every_turtle_of_both_simulators_in_tf(self):
        check = TfPoseCheck({'turtle1': '/turtle1/pose', 'sim2/turtle1': '/sim2/turtle1/pose'},
                            Pose)
        self.addCleanup(check.close)
        check.wait_agree(START_DEADLINE_S)

    def test_spawned_turtle_joins_moves_and_leaves(self):
        rospy.ServiceProxy('/spawn', Spawn)(2.0, 3.0, 1.0, 'robot2')
        check = TfPoseCheck({'robot2': '/robot2/pose'}, Pose)
        self.addCleanup(check.close)
        check.wait_agree(EVENT_DEADLINE_S)
        rospy.ServiceProxy('/robot2/teleport_absolute', TeleportAbsolute)(8.0, 1.0, -2.0)
        wait_for(lambda: check.mismatch('robot2') is None and check.buffer.lookup_transform(
            'world', 'robot2', rospy.Time(0)).transform.translation.x > 7.9,
            EVENT_DEADLINE_S, 'robot2 at x 8 in tf after the teleport')
        wait_for(lambda: self.marker('name', 'robot2'), EVENT_DEADLINE_S,
                 "robot2's name marker")
        rospy.ServiceProxy('/kill', Kill)('robot2')
        wait_for(lambda: '/pose_to_tf' not in subscribers_of('/robot2/pose'), EVENT_DEADLINE_S,
                 'pose_to_tf to drop /robot2/pose after the kill')
        wait_for(lambda: '/lesson_markers' not in subscribers_of('/robot2/pose'), EVENT_DEADLINE_S,
                 'lesson_markers to drop /robot2/pose after the kill')
        wait_for(lambda: self.markers is not None and not self.marker('name', 'robot2'),
                 EVENT_DEADLINE_S, "robot2's markers gone")

    def test_markers_show_arena_arrows_names_and_trails(self):
        arena = wait_for(lambda: self.marker('arena'), START_DEADLINE_S, 'the arena marker')
        self.assertEqual(arena.header.frame_id, 'world')
        corners = [(0, 0), (WORLD, 0), (WORLD, WORLD), (0, WORLD), (0, 0)]
        self.assertEqual(len(arena.points), len(corners))
        for point, (x, y) in zip(arena.points, corners, strict=True):
            self.assertAlmostEqual(point.x, x, delta=POSE_TOL)
            self.assertAlmostEqual(point.y, y, delta=POSE_TOL)
        for frame in ('turtle1', 'sim2/turtle1'):
            name = wait_for(lambda f=frame: self.marker('name', f), START_DEADLINE_S,
                            'the name marker of %s' % frame)
            self.assertEqual(name.header.frame_id, frame)
            self.assertTrue(name.frame_locked)
        arrows = {m.header.frame_id for m in self.markers.markers if m.ns == 'robot'}
        self.assertLessEqual({'turtle1', 'sim2/turtle1'}, arrows)
        # A trail appears once the turtle has moved: two points 0.05 m apart or more.
        rospy.ServiceProxy('/sim2/turtle1/teleport_absolute', TeleportAbsolute)(3.0, 3.0, 0.0)
        trail = wait_for(lambda: [m for m in (self.markers.markers if self.markers else [])
                                  if m.ns == 'trail' and len(m.points) >= 2
                                  and (m.points[-1].x, m.points[-1].y) == (3.0, 3.0)],
                         EVENT_DEADLINE_S, "sim2/turtle1's trail ending at (3, 3)")[0]
        self.assertEqual(trail.header.frame_id, 'world')

    def test_tf_echo_and_view_frames_show_the_turtles(self):
        with tempfile.TemporaryDirectory() as tmp:
            with spawn(['rosrun', 'tf', 'tf_echo', 'world', 'sim2/turtle1']) as echo:
                line = echo.wait_line('Translation', TOOL_DEADLINE_S)
            self.assertIn('Translation: [', line)
            frames = subprocess.run(['rosrun', 'tf2_tools', 'view_frames.py'], cwd=tmp,
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                    text=True, timeout=TOOL_DEADLINE_S)
            self.assertEqual(frames.returncode, 0, frames.stdout)
            with open(os.path.join(tmp, 'frames.gv')) as f:
                graph = f.read()
            for frame in ('"world" -> "turtle1"', '"world" -> "sim2/turtle1"'):
                self.assertIn(frame, graph)

    def test_bad_parameters_exit_with_a_clear_line(self):
        cases = (('pose_to_tf', '_rate_hz:=-1', '~rate_hz'),
                 ('pose_to_tf', '_discovery_period_s:=nan', '~discovery_period_s'),
                 ('pose_to_tf', '_turtles:=robot1', '~turtles'),
                 ('lesson_markers', '_trail_points:=1', '~trail_points'),
                 ('lesson_markers', '_parent_frame:=""', '~parent_frame'))
        for k, (exe, arg, name) in enumerate(cases):
            with self.subTest(exe=exe, arg=arg):
                # A node name of its own per case: private parameters stay on the master.
                result = subprocess.run(['rosrun', 'turtle_lite', exe, arg,
                                         '__name:=bad_%s_%d' % (exe, k)], stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True,
                                        timeout=TOOL_DEADLINE_S)
                self.assertNotEqual(result.returncode, 0, result.stdout)
                self.assertIn('parameter %s = ' % name, result.stdout)

    def test_rviz_shows_the_simulator_view(self):
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'rviz',
                            'turtlesim.rviz')
        with RvizOnXvfb(path, 'rviz_under_test') as rviz:
            rviz.capture(os.path.join(results_dir(), 'turtlesim_rviz.png'), robots=2, labels=2,
                         timeout_s=START_DEADLINE_S * 2)
            self.assertEqual(rviz.missing_topics(), [])
            self.assertEqual(rviz.topics, ['/lesson_markers', '/tf', '/tf_static'])
            self.assertEqual(error_lines(rviz.log()), [], rviz.log())


if __name__ == '__main__':
    rostest.rosrun('turtle_lite', 'lesson_views', LessonViewsTest, sys.argv)
