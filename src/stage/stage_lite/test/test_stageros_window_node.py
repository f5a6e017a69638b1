#!/usr/bin/env python3
"""stageros's window under Xvfb, driven as a user drives it (xdotool's keys and mouse).

The world (worlds/node_window.world) asks for a 640 x 400 window centred on (1, 0), turned 30
degrees, at 40 px/m. On the screen: the window's title and size, the four robots where that
camera puts them (their spacing gives the scale, their bearing the turn), each laser fan in
its robot's colour laid over the floor, and a status line that changes as /clock advances.
Then the Run keys (p pauses /clock, '.' steps once, '}' runs flat out, '{' real time again),
the mouse (a drag pans the view by the drag, a wheel notch zooms 1.1 x about the pointer,
space resets the view), a resize (the centre stays in the middle, the scale stays); the
close button (the window goes, the simulation runs on) and File -> Exit's Ctrl+Q (stageros
ends), each on a stageros of its own. The screenshot goes beside the test's results.
"""
import math
import os
import subprocess
import time
import unittest

import numpy as np
import rospy
import rostest
from course_common.rospy_internals import caller_id
from course_common.testing import (
    EVENT_DEADLINE_S,
    WaitError,
    Xvfb,
    results_dir,
    spawn,
    wait_for,
)
from course_common.testing.recorders import Recorder, stamp_ns
from course_common.testing.x_windows import XWindows
from PIL import ImageGrab
from rosgraph_msgs.msg import Clock
from stage_support import STAGEROS, START_DEADLINE_S, STEP_NS, world

WORLD = world('node_window.world')
TITLE = 'Stage: node_window.world'
SIZE_PX = (640, 400)
SCALE_PX_PER_M = 40.0
YAW_DEG = 30.0
#: The robots' colours and body centres (pose plus the -0.05 m origin along the heading).
ROBOTS = {'blue': ((0, 0, 255), (1.95 - 0.05, 1.0)),
          'red': ((255, 0, 0), (-0.05, 1.0 - 0.05)),
          'green': ((0, 255, 0), (1.95, -1.0 + 0.05)),
          'magenta': ((255, 0, 255), (-0.05 + 0.05, -1.0))}
#: A fan: the robot's colour over the floor (white or the grid's 245/245/255) at 38/255.
FAN_OPACITY = 38 / 255
FLOOR_RGB = ((255, 255, 255), (245, 245, 255))
MIN_FAN_PX = 1000       # each fan has thousands of pixels no other fan covers
PX_TOL = 1.5            # a body's centre in a screenshot: whole pixels, a drawn outline
CLOCK_BOX_RGB = (204, 204, 255)
PAUSE_SETTLE_S = 0.5    # /clock silent this long: the pause is in effect
PAUSE_WATCH_S = 1.0     # ... and stays silent this much longer
RATE_WATCH_S = 2.0      # wall time over which the real-time factor is measured


def screen_vector(dx, dy):
    """A world vector as Stage's camera shows it: turned by -yaw, scaled, y down."""
    a = math.radians(YAW_DEG)
    u = math.cos(a) * dx + math.sin(a) * dy
    v = -math.sin(a) * dx + math.cos(a) * dy
    return np.array([u, -v]) * SCALE_PX_PER_M


class StagerosWindowTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('stageros_window_test')
        cls.xvfb = Xvfb()
        cls.display = cls.xvfb.display
        cls.xwin = XWindows(cls.display)
        cls.node = spawn(STAGEROS + [WORLD], env=cls.xvfb.env())
        # this stageros's clock only: two tests start one of their own beside it
        cls.clock = Recorder('/clock', Clock, keep=1,
                             accept=lambda m: caller_id(m) == '/stageros')
        cls.window = wait_for(lambda: cls.xwin.mapped(TITLE), START_DEADLINE_S,
                              'a mapped window titled %r' % TITLE, alive=cls.node.alive)[0]
        cls.clock.wait_latest(lambda m: stamp_ns(m) >= 5 * STEP_NS, 'half a second of sim time',
                              START_DEADLINE_S)

    @classmethod
    def tearDownClass(cls):
        cls.clock.close()
        cls.node.stop()
        cls.xwin.close()
        cls.xvfb.close()

    # what the test sees and does
    def shot(self, name=None):
        """The window's pixels (rows x cols x RGB); saved beside the results if named."""
        x, y = self.window.x, self.window.y
        image = ImageGrab.grab(xdisplay=self.display).crop((x, y, x + SIZE_PX[0],
                                                            y + SIZE_PX[1]))
        if name:
            image.save(os.path.join(results_dir(), name))
        return np.asarray(image.convert('RGB')).astype(int)

    def bodies(self, pixels):
        """{robot: (col, row) of its body's centre}: the mean of its pure colour's pixels."""
        found = {}
        for name, (rgb, _) in ROBOTS.items():
            rows, cols = np.nonzero((pixels == rgb).all(axis=2))
            if len(rows):
                found[name] = np.array([cols.mean(), rows.mean()])
        return found

    def bodies_where(self, check, what):
        """The bodies on screen once check(bodies) holds (the window draws an event at its
        next frame); a failure shows where they were last."""
        last = {}

        def holds():
            last['bodies'] = self.bodies(self.shot())
            ok = len(last['bodies']) == len(ROBOTS) and check(last['bodies'])
            return last['bodies'] if ok else None
        try:
            return wait_for(holds, EVENT_DEADLINE_S, what)
        except WaitError:
            self.fail('%s: the bodies stayed at %r' % (what, last.get('bodies')))

    def moved_by(self, start, offset):
        """A check: every body moved by offset (px) from start."""
        return lambda now: all(np.abs(now[k] - start[k] - offset).max() <= PX_TOL for k in now)

    def xdo(self, *args):
        subprocess.run(['xdotool'] + [str(a) for a in args], env=self.xvfb.env(), check=True,
                       timeout=EVENT_DEADLINE_S)

    def key(self, name):
        self.xdo('windowfocus', '--sync', self.window.id)
        self.xdo('key', name)

    def sim_ns(self):
        return stamp_ns(self.clock.latest())

    def wait_paused(self):
        """Until /clock stays silent for PAUSE_SETTLE_S; its last time."""
        seen = {'ns': None, 'since': None}

        def silent():
            now, ns = time.monotonic(), self.sim_ns()
            if ns != seen['ns']:
                seen.update(ns=ns, since=now)
            return ns if now - seen['since'] >= PAUSE_SETTLE_S else None
        return wait_for(silent, EVENT_DEADLINE_S, '/clock to stop')

    def rate(self):
        """Sim seconds per wall second over RATE_WATCH_S."""
        t0, s0 = time.monotonic(), self.sim_ns()
        wait_for(lambda: time.monotonic() - t0 >= RATE_WATCH_S, RATE_WATCH_S + 5, 'the watch')
        return (self.sim_ns() - s0) * 1e-9 / (time.monotonic() - t0)

    # the tests: each leaves the window as it found it (running at real time, the world's
    # view); closing and exiting use a stageros of their own
    def test_window_has_the_worlds_size_scale_and_turn(self):
        self.assertEqual((self.window.width, self.window.height), SIZE_PX)
        self.assertNotIn('without a window', self.node.output())
        bodies = self.bodies_where(lambda b: True, 'all four robots on screen')
        self.shot('stageros_window.png')
        for a, b in (('red', 'blue'), ('magenta', 'red'), ('green', 'magenta')):
            world = np.subtract(ROBOTS[b][1], ROBOTS[a][1])
            np.testing.assert_allclose(bodies[b] - bodies[a], screen_vector(*world),
                                       atol=PX_TOL, err_msg='%s -> %s' % (a, b))
        # the camera's centre (1, 0) is the middle of the view, across the whole width
        middle = bodies['blue'] - screen_vector(*np.subtract(ROBOTS['blue'][1], (1.0, 0.0)))
        self.assertAlmostEqual(middle[0], SIZE_PX[0] / 2, delta=PX_TOL)

    def test_each_fan_shows_in_its_robots_colour(self):
        pixels = self.shot()
        for name, (rgb, _) in ROBOTS.items():
            tinted = 0
            for floor in FLOOR_RGB:
                expected = np.add(floor, FAN_OPACITY * np.subtract(rgb, floor))
                tinted += (np.abs(pixels - expected).max(axis=2) <= 1).sum()
            self.assertGreater(tinted, MIN_FAN_PX, '%s fan: %d px' % (name, tinted))

    def status_box(self, pixels):
        rows, cols = np.nonzero((pixels == CLOCK_BOX_RGB).all(axis=2))
        self.assertTrue(len(rows), 'the status line is drawn')
        return pixels[rows.min():rows.max() + 1, cols.min():cols.max() + 1]

    def test_status_line_follows_the_clock(self):
        before = self.status_box(self.shot())
        start = self.sim_ns()
        self.clock.wait_latest(lambda m: stamp_ns(m) >= start + 10 * STEP_NS, 'a second more')

        def changed():
            return not np.array_equal(self.status_box(self.shot()), before)
        wait_for(changed, EVENT_DEADLINE_S, 'the status line to show the new time')

    def test_run_keys_pause_step_and_change_the_speed(self):
        self.key('p')
        paused_at = self.wait_paused()
        box = self.status_box(self.shot())
        t0 = time.monotonic()
        wait_for(lambda: time.monotonic() - t0 >= PAUSE_WATCH_S, PAUSE_WATCH_S + 5, 'a watch')
        self.assertEqual(self.sim_ns(), paused_at, 'paused: /clock stands still')
        self.assertTrue(np.array_equal(box, self.status_box(self.shot())),
                        'paused: the status line stands still')
        self.key('period')
        self.clock.wait_latest(lambda m: stamp_ns(m) == paused_at + STEP_NS, 'one step')
        self.assertEqual(self.wait_paused(), paused_at + STEP_NS, 'one step, then still')
        self.key('braceright')          # Run -> Fast, still paused
        self.key('p')                   # ... and on: flat out
        flat_out = self.rate()
        self.key('braceleft')           # Run -> Realtime
        real_time = self.rate()
        self.assertGreater(flat_out, 3.0, 'flat out: %.1f x real time' % flat_out)
        self.assertLess(real_time, 2.0, 'real time again: %.2f x' % real_time)
        self.assertIn('as fast as possible', self.node.output())

    def test_drag_pans_wheel_zooms_about_the_pointer_space_resets(self):
        home = self.bodies_where(lambda b: True, 'the robots on screen')
        x0, y0 = self.window.x + 100, self.window.y + SIZE_PX[1] - 100
        self.xdo('mousemove', x0, y0)
        self.xdo('mousedown', 1)
        for k in (1, 2, 3):
            self.xdo('mousemove', x0 + 20 * k, y0 - 10 * k)
        self.xdo('mouseup', 1)
        panned = self.bodies_where(self.moved_by(home, (60, -30)), 'the view dragged along')
        bx, by = np.rint(panned['blue']).astype(int)
        self.xdo('mousemove', self.window.x + bx, self.window.y + by)
        self.xdo('click', 4)            # the wheel, one notch up: zoom in about the pointer

        def zoomed_about_blue(now):
            spread = np.linalg.norm(now['red'] - now['blue'])
            before = np.linalg.norm(panned['red'] - panned['blue'])
            return (np.abs(now['blue'] - panned['blue']).max() <= PX_TOL
                    and abs(spread / before - 1.1) <= 0.03)
        self.bodies_where(zoomed_about_blue, 'the view zoomed 1.1 x about the blue robot')
        self.key('space')
        self.bodies_where(self.moved_by(home, (0, 0)), 'the view back home (View -> Reset)')

    def test_resizing_keeps_the_centre_and_the_scale(self):
        home = self.bodies_where(lambda b: True, 'the robots on screen')
        self.xdo('windowsize', '--sync', self.window.id, SIZE_PX[0] + 160, SIZE_PX[1] + 100)
        # the view's middle moves by half the growth; the robots keep their spacing
        self.bodies_where(self.moved_by(home, (80, 50)), 'the view after the resize')
        self.xdo('windowsize', '--sync', self.window.id, *SIZE_PX)
        self.bodies_where(self.moved_by(home, (0, 0)), 'the view after the resize back')

    def own_stageros(self, name):
        """A second stageros (node `name`) with its window on a display of its own, stopped
        after the test: (its XWindows, the process, its window)."""
        xvfb = Xvfb()
        self.addCleanup(xvfb.close)
        xwin = XWindows(xvfb.display)
        self.addCleanup(xwin.close)
        node = spawn(STAGEROS + [WORLD, '__name:=' + name], env=xvfb.env())
        self.addCleanup(node.stop)
        window = wait_for(lambda: xwin.mapped(TITLE), START_DEADLINE_S, "%s's window" % name,
                          alive=node.alive)[0]
        return xvfb, xwin, node, window

    def test_closing_the_window_leaves_the_simulation_running(self):
        _, xwin, node, window = self.own_stageros('stageros_closed')
        xwin.ask_to_close(window.id)
        wait_for(lambda: not xwin.mapped(TITLE), EVENT_DEADLINE_S, 'the window to go')
        clock = Recorder('/clock', Clock)
        self.addCleanup(clock.close)
        wait_for(lambda: len(clock.messages('/stageros_closed')) >= 5, EVENT_DEADLINE_S,
                 "/stageros_closed's /clock after its window closed")
        times = [stamp_ns(m) for m in clock.messages('/stageros_closed')]
        self.assertEqual(times, sorted(set(times)), 'its clock goes on')
        self.assertTrue(node.alive())
        self.assertIn('simulation runs on', node.output())

    def test_file_exit_ends_stageros(self):
        xvfb, _, node, window = self.own_stageros('stageros_exit')
        env = xvfb.env()
        subprocess.run(['xdotool', 'windowfocus', '--sync', str(window.id)], env=env,
                       check=True, timeout=EVENT_DEADLINE_S)
        subprocess.run(['xdotool', 'key', 'ctrl+q'], env=env, check=True,
                       timeout=EVENT_DEADLINE_S)
        self.assertEqual(node.wait_exit(EVENT_DEADLINE_S), 0, node.tail())
        self.assertIn('File -> Exit', node.output())


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_window', StagerosWindowTest)
