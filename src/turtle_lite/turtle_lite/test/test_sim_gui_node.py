#!/usr/bin/env python3
"""The Tk window of turtlesim_node (~gui:=true) under Xvfb: title, size, background, turtle."""

import ctypes
import ctypes.util
import os
import tempfile
import unittest

import numpy as np
import rospy
import rostest
from course_common.testing import START_DEADLINE_S, Xvfb, spawn, wait_for
from PIL import ImageGrab
from sim_support import DEFAULT_BG
from turtlesim.srv import TeleportAbsolute

SCREEN = (800, 600)


class XWindows:
    """Just enough Xlib (through ctypes, no extra package) to list window names and sizes."""

    class Attributes(ctypes.Structure):
        _fields_ = [('x', ctypes.c_int), ('y', ctypes.c_int), ('width', ctypes.c_int),
                    ('height', ctypes.c_int), ('border_width', ctypes.c_int),
                    ('depth', ctypes.c_int), ('visual', ctypes.c_void_p),
                    ('root', ctypes.c_ulong), ('class', ctypes.c_int),
                    ('bit_gravity', ctypes.c_int), ('win_gravity', ctypes.c_int),
                    ('backing_store', ctypes.c_int), ('backing_planes', ctypes.c_ulong),
                    ('backing_pixel', ctypes.c_ulong), ('save_under', ctypes.c_int),
                    ('colormap', ctypes.c_ulong), ('map_installed', ctypes.c_int),
                    ('map_state', ctypes.c_int), ('all_event_masks', ctypes.c_long),
                    ('your_event_mask', ctypes.c_long),
                    ('do_not_propagate_mask', ctypes.c_long),
                    ('override_redirect', ctypes.c_int), ('screen', ctypes.c_void_p)]

    def __init__(self, display):
        self.x = ctypes.cdll.LoadLibrary(ctypes.util.find_library('X11') or 'libX11.so.6')
        self.x.XOpenDisplay.restype = ctypes.c_void_p
        self.x.XOpenDisplay.argtypes = [ctypes.c_char_p]
        self.x.XDefaultRootWindow.restype = ctypes.c_ulong
        self.x.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
        self.x.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                      ctypes.POINTER(ctypes.c_ulong),
                                      ctypes.POINTER(ctypes.c_ulong),
                                      ctypes.POINTER(ctypes.POINTER(ctypes.c_ulong)),
                                      ctypes.POINTER(ctypes.c_uint)]
        self.x.XFetchName.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                      ctypes.POINTER(ctypes.c_char_p)]
        self.x.XGetWindowAttributes.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                                ctypes.POINTER(self.Attributes)]
        self.x.XFree.argtypes = [ctypes.c_void_p]
        self.x.XCloseDisplay.argtypes = [ctypes.c_void_p]
        self.dpy = self.x.XOpenDisplay(display.encode())
        if not self.dpy:
            raise RuntimeError('cannot open display %s' % display)

    def close(self):
        self.x.XCloseDisplay(self.dpy)

    def windows(self):
        """[(name, width, height, mapped)] of every named window on the screen."""
        found = []
        stack = [self.x.XDefaultRootWindow(self.dpy)]
        while stack:
            win = stack.pop()
            name = ctypes.c_char_p()
            if self.x.XFetchName(self.dpy, win, ctypes.byref(name)) and name.value:
                attrs = self.Attributes()
                self.x.XGetWindowAttributes(self.dpy, win, ctypes.byref(attrs))
                found.append((name.value.decode(), attrs.width, attrs.height,
                              attrs.map_state == 2))
            root = ctypes.c_ulong()
            parent = ctypes.c_ulong()
            children = ctypes.POINTER(ctypes.c_ulong)()
            count = ctypes.c_uint()
            if self.x.XQueryTree(self.dpy, win, ctypes.byref(root), ctypes.byref(parent),
                                 ctypes.byref(children), ctypes.byref(count)):
                stack.extend(children[i] for i in range(count.value))
                if children:
                    self.x.XFree(children)
        return found


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
        window = wait_for(lambda: [w for w in xwin.windows() if w[0] == 'TurtleSim' and w[3]],
                          START_DEADLINE_S, 'a mapped window titled TurtleSim')[0]
        self.assertEqual(window[1:3], (500, 500), self.output())
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
