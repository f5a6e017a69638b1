#!/usr/bin/env python3
"""The Tk window of turtlesim_node (~gui:=true) under Xvfb: title, size, background, turtle."""

import os
import tempfile
import unittest

import numpy as np
import rospy
import rostest
from course_common.testing import START_DEADLINE_S, Xvfb, spawn, wait_for
from course_common.testing.x_windows import XWindows
from PIL import ImageGrab
from sim_support import DEFAULT_BG
from turtlesim.srv import TeleportAbsolute

SCREEN = (800, 600)


class SimGuiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_sim_gui')
        cls.xvfb = Xvfb(SCREEN)
        cls.display = cls.xvfb.display
        cls.sim = spawn(['rosrun', 'turtle_lite', 'turtlesim_node', '_gui:=true'],
                        env={'DISPLAY': cls.display, 'ROS_NAMESPACE': 'gui'})
        rospy.wait_for_service('/gui/turtle1/teleport_absolute', START_DEADLINE_S)

    @classmethod
    def tearDownClass(cls):
        cls.sim.stop()
        cls.xvfb.close()

    def output(self):
        return self.sim.output()

    def test_window_title_size_background_and_turtle(self):
        xwin = XWindows(self.display)
        self.addCleanup(xwin.close)
        window = wait_for(lambda: xwin.mapped('TurtleSim'),
                          START_DEADLINE_S, 'a mapped window titled TurtleSim')[0]
        self.assertEqual((window.width, window.height), (500, 500), self.output())
        self.assertNotIn('running headless', self.output())

        rospy.ServiceProxy('/gui/turtle1/teleport_absolute', TeleportAbsolute)(2.0, 2.0, 0.0)

        def trail_visible():
            shot = np.asarray(ImageGrab.grab(xdisplay=self.display).convert('RGB'))
            pen = (shot == (179, 184, 255)).all(axis=2).sum()
            return [shot] if pen > 100 else None
        shot = wait_for(trail_visible, START_DEADLINE_S, "the teleport trail on screen")[0]
        tmp = os.environ.get('ROS_TEST_RESULTS_DIR', tempfile.gettempdir())
        try:
            from PIL import Image
            Image.fromarray(shot).save(os.path.join(tmp, 'turtle_lite_gui_screenshot.png'))
        except OSError:
            pass
        background = (shot == DEFAULT_BG).all(axis=2).sum()
        self.assertGreater(background, 0.8 * 500 * 500, 'the background fills the window')
        self.assertLess(background, 500 * 500, 'only inside the 500x500 window')
        # The turtle sprite: greens that are neither background nor pen.
        greenish = ((shot[:, :, 1] > shot[:, :, 0] + 30) & (shot[:, :, 1] > shot[:, :, 2])).sum()
        self.assertGreater(greenish, 100, 'a turtle sprite is drawn')


if __name__ == '__main__':
    rostest.rosrun('turtle_lite', 'sim_gui', SimGuiTest)
