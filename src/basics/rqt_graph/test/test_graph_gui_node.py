#!/usr/bin/env python3
"""rqt_graph's Tk window under Xvfb: it shows the graph and follows nodes coming and going."""
import os
import signal
import subprocess
import threading
import unittest

import numpy as np
import rostest
from course_common.testing import wait_for
from graph_support import GRAPH_DEADLINE_S, results_dir
from PIL import ImageGrab

PKG = 'rqt_graph'
SCREEN = '1024x768x24'
EXIT_DEADLINE_S = 15.0
WHITE_MIN_PX = 20000  # the picture's white background: a 400x60 graph at the least
DARK_MIN_PX = 500  # its ellipses, box, arrows and labels


class Lines:
    """A process's stdout lines, read by a thread as they come."""

    def __init__(self, stream):
        self._lock = threading.Lock()
        self._lines = []
        threading.Thread(target=self._read, args=(stream,), daemon=True).start()

    def _read(self, stream):
        for line in stream:
            with self._lock:
                self._lines.append(line.rstrip('\n'))

    def count(self, text):
        with self._lock:
            return sum(text in line for line in self._lines)

    def all(self):
        with self._lock:
            return '\n'.join(self._lines)


class TestGraphGui(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # -displayfd: Xvfb picks a free display number and writes it to us.
        cls.xvfb = subprocess.Popen(['Xvfb', '-displayfd', '1', '-screen', '0', SCREEN,
                                     '-nolisten', 'tcp'],
                                    stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        cls.display = ':' + cls.xvfb.stdout.readline().decode().strip()
        cls.tool = subprocess.Popen(['rosrun', 'rqt_graph', 'rqt_graph'], text=True,
                                    env=dict(os.environ, DISPLAY=cls.display),
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        cls.lines = Lines(cls.tool.stdout)

    @classmethod
    def tearDownClass(cls):
        for proc in (cls.tool, cls.xvfb):
            if proc.poll() is None:
                proc.kill()
                proc.wait(EXIT_DEADLINE_S)

    def wait_line(self, text, times=1):
        wait_for(lambda: self.lines.count(text) >= times, GRAPH_DEADLINE_S,
                 '"%s" (x%d) from the window; output so far:\n%s'
                 % (text, times, self.lines.all()))

    def screen(self):
        return np.asarray(ImageGrab.grab(xdisplay=self.display).convert('RGB')).astype(int)

    def test_window_follows_the_graph(self):
        self.wait_line('rqt_graph: showing 2 nodes, 1 topic')

        def drawn():
            shot = self.screen()
            white = (shot == 255).all(axis=2).sum()
            dark = (shot.sum(axis=2) < 200).sum() - (shot == 0).all(axis=2).sum()
            return [shot] if white > WHITE_MIN_PX and dark > DARK_MIN_PX else None
        before = wait_for(drawn, GRAPH_DEADLINE_S, 'the graph drawn on screen')[0]
        ImageGrab.grab(xdisplay=self.display).save(
            os.path.join(results_dir(), 'rqt_graph_window.png'))

        talker2 = subprocess.Popen(['rosrun', 'chat_pkg', 'talker', '__name:=talker2'],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            self.wait_line('rqt_graph: showing 3 nodes, 1 topic')
            wait_for(lambda: (self.screen() != before).any(axis=2).sum() > DARK_MIN_PX,
                     GRAPH_DEADLINE_S, 'the window to draw talker2')
        finally:
            talker2.send_signal(signal.SIGINT)
            talker2.wait(EXIT_DEADLINE_S)
        self.wait_line('rqt_graph: showing 2 nodes, 1 topic', times=2)

        self.tool.send_signal(signal.SIGINT)  # Ctrl-C in the terminal closes the window
        self.assertEqual(self.tool.wait(EXIT_DEADLINE_S), 0, self.lines.all())
        self.assertNotIn('Traceback', self.lines.all())


if __name__ == '__main__':
    rostest.rosrun(PKG, 'graph_gui', TestGraphGui)
