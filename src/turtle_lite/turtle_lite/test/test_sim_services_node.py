#!/usr/bin/env python3
"""turtlesim_node services, names and params, and PNGs."""

import os
import shutil
import tempfile
import threading

import numpy as np
import rospy
import rostest
from course_common.testing import wait_for
from course_common.testing.master import graph_names, names_under
from course_msgs.srv import SaveImage
from PIL import Image
from rosgraph_msgs.msg import Log
from sim_support import DEFAULT_BG, DEFAULT_PEN, SimTestCase, has_turtle_at, wait_connected
from turtle_lite.testing import CENTER, POSE_TOL, WORLD, PoseRecorder
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute


class SimServicesTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.save_image = rospy.ServiceProxy('/turtlesim/save_image', SaveImage)
        cls.tmp = tempfile.mkdtemp(prefix='turtle_lite_test_')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def setUp(self):
        rospy.set_param('/turtlesim/background_r', 69)
        rospy.set_param('/turtlesim/background_g', 86)
        rospy.set_param('/turtlesim/background_b', 255)
        self.reset()
        self.pose.wait(lambda p: abs(p.x - CENTER) < POSE_TOL, 'turtle1 back at the centre')

    def assert_fails(self, call, *args):
        with self.assertRaises(rospy.ServiceException, msg=repr(args)):
            call(*args)

    def test_name_counter(self):
        """turtle_frame.cpp's naming: the next free turtleN."""
        self.assertEqual(self.spawn(1, 1, 0, 'turtle3').name, 'turtle3')
        self.assertEqual(self.spawn(1, 1, 0, '').name, 'turtle2')
        self.assertEqual(self.spawn(1, 1, 0, '').name, 'turtle4')
        self.kill('turtle2')
        self.assertEqual(self.spawn(1, 1, 0, '').name, 'turtle5')
        self.reset()
        self.assertEqual(self.spawn(1, 1, 0, '').name, 'turtle2')

    def test_error_paths_and_accepted_names(self):
        """Items 10 and 17: failures reach the client; turtlesim's ERROR lines."""
        self.assert_fails(self.spawn, 1, 1, 0, 'turtle1')
        self.logs.wait_line('A turtled named [turtle1] already exists', Log.ERROR)
        self.assert_fails(self.kill, 'nobody')
        self.logs.wait_line('Tried to kill turtle [nobody], which does not exist', Log.ERROR)
        for name, text in (
                ('my turtle', 'Character [ ] at element [2] is not valid in Graph Resource '
                              'Name [my turtle].  Valid characters are a-z, A-Z, 0-9, / and _.'),
                ('1abc', 'Character [1] is not valid as the first character in Graph Resource '
                         'Name [1abc].  Valid characters are a-z, A-Z, / and in some cases ~.'),
                ('_u', 'Character [_] is not valid as the first character'),
                ('a-b', 'Character [-] at element [1] is not valid')):
            with self.assertRaises(rospy.ServiceException) as err:
                self.spawn(1, 1, 0, name)
            self.assertIn(text, str(err.exception))
            self.logs.wait_line('Exception thrown while processing service call: ' + text,
                                Log.ERROR)
            self.assertFalse([line for line in self.logs.lines()
                              if line.startswith('Spawning turtle [%s]' % name)])
        for name, namespace in (('/abs', '/abs'), ('grp/t', '/grp/t'),
                                ('~priv', '/turtlesim/priv')):
            self.assertEqual(self.spawn(2, 2, 0, name).name, name)
            wait_for(lambda ns=namespace: has_turtle_at(ns), 10, 'resources under ' + namespace)
        self.assert_fails(self.kill, 'abs')  # the registry key is the raw string
        self.kill('/abs')
        wait_for(lambda: not names_under('/abs'), 10, '/abs to be unregistered')

    def test_spawn_is_not_validated_but_clamped_on_first_tick(self):
        """Item 11."""
        self.spawn(-2.0, 20.0, 7.0, 'clampy')
        self.logs.wait_line('Spawning turtle [clampy] at x=[-2.000000], y=[20.000000], '
                            'theta=[7.000000]', Log.INFO)
        self.logs.wait_line('Oh no! I hit the wall! (Clamping from [x=-2.000000, '
                            'y=-8.911111])', Log.WARN)
        clampy = PoseRecorder('/clampy/pose')
        self.addCleanup(clampy.close)
        pose = clampy.wait(lambda p: True, 'a pose of clampy')
        self.assertEqual(pose.x, 0.0)
        self.assertAlmostEqual(pose.y, WORLD, delta=POSE_TOL)
        self.assertAlmostEqual(pose.theta, 0.7168147, delta=2e-7)

    def test_reset(self):
        """Item 12."""
        self.spawn(1, 1, 0, 'extra')
        wait_for(lambda: has_turtle_at('/extra'), 10, '/extra resources')
        self.set_pen(255, 0, 0, 9, 0)
        self.absolute(2.0, 2.0, 1.0)
        self.pose.wait(lambda p: abs(p.x - 2.0) < POSE_TOL, 'turtle1 moved away')
        rospy.set_param('/turtlesim/background_r', 10)
        self.reset()
        wait_for(lambda: not names_under('/extra'), 10, '/extra to be unregistered by reset')
        pose = self.pose.wait(lambda p: abs(p.x - CENTER) < POSE_TOL, 'turtle1 respawned')
        self.assertAlmostEqual(pose.y, CENTER, delta=POSE_TOL)
        self.assertEqual(pose.theta, 0.0)
        self.color.wait_rgb((10, 86, 255), 'the background re-read by reset')
        self.absolute(3.0, 3.0, 0.0)
        self.color.wait_rgb(DEFAULT_PEN, 'the default pen after reset')
        lines = self.logs.lines(Log.INFO)
        i_reset = max(i for i, line in enumerate(lines) if line == 'Resetting turtlesim.')
        self.assertTrue(lines[i_reset + 1].startswith('Spawning turtle [turtle1] at '
                                                      'x=[5.544445], y=[5.544445]'),
                        lines[i_reset:])

    def test_clear_and_background_params(self):
        """Item 13."""
        self.color.wait_rgb(DEFAULT_BG, 'the default background')
        rospy.set_param('/turtlesim/background_g', 200)
        self.color.wait_count(30)
        self.assertEqual(self.color.messages()[-1].g, 86, 'params are read on clear only')
        self.set_pen(1, 2, 3, 3, 0)
        self.clear()
        self.logs.wait_line('Clearing turtlesim.', Log.INFO)
        self.color.wait_rgb((69, 200, 255), 'the new background after clear')
        rospy.delete_param('/turtlesim/background_g')
        self.clear()
        self.color.wait_rgb(DEFAULT_BG, 'the default for a deleted param')
        self.color.wait_count(10)
        self.assertFalse(rospy.has_param('/turtlesim/background_g'), 'not re-created')
        # Clear keeps the turtle and its pen.
        self.absolute(4.0, 4.0, 0.0)
        self.color.wait_rgb((1, 2, 3), 'the pen set before clear')
        self.assertAlmostEqual(self.pose.wait(lambda p: p.x == 4.0, 'turtle1 at x=4').y, 4.0,
                               delta=POSE_TOL)

    def test_set_pen(self):
        """Item 14, through color_sensor."""
        self.color.wait_rgb(DEFAULT_BG, 'the background under a fresh turtle')
        self.absolute(3.0, 3.0, 0.0)
        self.color.wait_rgb(DEFAULT_PEN, 'the default pen (179, 184, 255)')
        self.set_pen(255, 0, 0, 0, 0)
        self.absolute(3.0, 6.0, 0.0)
        self.color.wait_rgb((255, 0, 0), 'the new pen colour')
        self.set_pen(0, 255, 0, 7, 1)  # off: colour and width ignored
        self.absolute(6.0, 6.0, 0.0)
        self.color.wait_rgb(DEFAULT_BG, 'no trail with the pen off')
        self.set_pen(0, 0, 255, 0, 0)
        self.absolute(6.0, 9.0, 0.0)
        self.color.wait_rgb((0, 0, 255), 'the pen back on')
        # Width 0 draws 1 px: the vertical red trail from (3, 3) to (3, 6) is 1 column wide.
        path = self.save_image(os.path.join(self.tmp, 'pen.png')).path
        with Image.open(path) as image:
            pixels = np.asarray(image.convert('RGB'))
        row = pixels[int(round((WORLD - 4.5) * 45))]
        red_cols = np.nonzero((row == (255, 0, 0)).all(axis=1))[0]
        self.assertEqual(len(red_cols), 1, red_cols)
        self.assertEqual(red_cols[0], 135)
        blue_row = pixels[int(round((WORLD - 7.5) * 45))]
        self.assertEqual(len(np.nonzero((blue_row == (0, 0, 255)).all(axis=1))[0]), 1)
        # The default pen (width 3) made a 3 px wide trail from the centre to (3, 3).
        self.assertFalse(len(np.nonzero((row == (0, 255, 0)).all(axis=1))[0]))

    def test_save_image_png(self):
        """The ~save_image extension: background, trails and sprites in a PNG."""
        self.cmd_drive_east()
        path = os.path.join(self.tmp, 'sub', 'drive.png')
        response = self.save_image(path)
        self.assertEqual(response.path, path)
        with Image.open(path) as image:
            self.assertEqual(image.size, (500, 500))
            self.assertEqual(image.format, 'PNG')
            pixels = np.asarray(image.convert('RGB'))
        self.assertEqual(tuple(pixels[5, 5]), DEFAULT_BG)
        self.assertEqual(tuple(pixels[490, 490]), DEFAULT_BG)
        # The trail 0.5 m east of the start (the sprite covers the end point).
        row = int(round((WORLD - CENTER) * 45))
        col = int(round((CENTER + 0.5) * 45))
        self.assertEqual(tuple(pixels[row, col]), DEFAULT_PEN)
        # The sprite sits at the turtle: neither background nor pen there.
        pose = self.pose.latest()
        sprite = tuple(pixels[int(round((WORLD - pose.y) * 45)), int(round(pose.x * 45))])
        self.assertNotIn(sprite, (DEFAULT_BG, DEFAULT_PEN))
        # An empty path writes ~image_path.
        self.assertEqual(self.save_image('').path,
                         '/tmp/turtle_lite_sim_services_test/default.png')
        self.assertTrue(os.path.isfile('/tmp/turtle_lite_sim_services_test/default.png'))
        self.assert_fails(self.save_image, '/proc/no/such/dir/x.png')

    def test_concurrent_calls_and_teleport_ordering(self):
        """Item 18: state is locked, teleports still land at the next tick."""
        errors = []

        def churn(prefix):
            try:
                spawn = rospy.ServiceProxy('/spawn', Spawn)
                kill = rospy.ServiceProxy('/kill', Kill)
                for i in range(8):
                    name = spawn(1.0 + i, 2.0, 0.0, '%s%d' % (prefix, i)).name
                    kill(name)
            except Exception as exc:  # collected and asserted below
                errors.append(exc)

        def teleports():
            try:
                absolute = rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)
                pen = rospy.ServiceProxy('/turtle1/set_pen', SetPen)
                for i in range(20):
                    absolute(1.0 + (i % 9), 1.0 + (i % 7), 0.1 * i)
                    pen(i, 2 * i, 3 * i, 1 + i % 4, i % 2)
            except Exception as exc:
                errors.append(exc)

        threads = [threading.Thread(target=churn, args=('c%d_' % k,)) for k in range(3)]
        threads.append(threading.Thread(target=teleports))
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(60)
        self.assertEqual(errors, [])
        wait_for(lambda: not [n for n in graph_names()[0] if n.startswith('/c')], 10,
                 'every churned turtle to be unregistered')
        self.assertEqual(self.spawn(1, 1, 0, '').name, 'turtle2')

        # The reply comes before the pose shows the teleport (it lands at the next tick).
        self.absolute(9.0, 3.0, 0.0)
        self.pose.wait(lambda p: abs(p.x - 9.0) < POSE_TOL, 'turtle1 at x = 9')
        late = 0
        for i in range(10):
            target = 2.0 + (i % 2) * 5.0
            self.pose.wait(lambda p, t=target: abs(p.x - t) > 1.0, 'away from the target')
            self.absolute(target, 3.0, 0.0)
            at_reply = self.pose.latest()
            late += abs(at_reply.x - target) < POSE_TOL
            self.pose.wait(lambda p, t=target: abs(p.x - t) < POSE_TOL, 'the teleport')
        # A tick can fall between the reply leaving the node and reaching us: rare.
        self.assertLessEqual(late, 3)

    def cmd_drive_east(self):
        from geometry_msgs.msg import Twist
        pub = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
        self.addCleanup(pub.unregister)
        wait_connected(pub, 'cmd_vel link')
        msg = Twist()
        msg.linear.x = 2.0
        pub.publish(msg)
        self.pose.wait(lambda p: p.x > CENTER + 1.5, 'turtle1 driving east')
        self.pose.wait_at_rest()


if __name__ == '__main__':
    rospy.init_node('test_sim_services')
    rostest.rosrun('turtle_lite', 'sim_services', SimServicesTest)
