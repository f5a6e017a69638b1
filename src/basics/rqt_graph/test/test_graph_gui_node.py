#!/usr/bin/env python3
"""rqt_graph's Tk window under Xvfb: it shows the graph and follows nodes coming and going."""
import os
import unittest

import numpy as np
import rostest
from course_common.testing import Xvfb, results_dir, spawn, wait_for
from graph_support import GRAPH_DEADLINE_S
from PIL import ImageGrab

PKG = 'rqt_graph'
SCREEN = (1024, 768)
EXIT_DEADLINE_S = 15.0
WHITE_MIN_PX = 20000  # the picture's white background: a 400x60 graph at the least
DARK_MIN_PX = 500  # its ellipses, box, arrows and labels


class TestGraphGui(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.xvfb = Xvfb(SCREEN)
        cls.display = cls.xvfb.display
        cls.tool = spawn(['rosrun', 'rqt_graph', 'rqt_graph'], env={'DISPLAY': cls.display})

    @classmethod
    def tearDownClass(cls):
        cls.tool.stop()
        cls.xvfb.close()

    def wait_line(self, text, times=1):
        wait_for(lambda: len(self.tool.lines_with(text)) >= times, GRAPH_DEADLINE_S,
                 '"%s" (x%d) from the window; output so far:\n%s'
                 % (text, times, self.tool.output()))

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

        talker2 = spawn(['rosrun', 'chat_pkg', 'talker', '__name:=talker2'])
        self.addCleanup(talker2.stop)
        try:
            self.wait_line('rqt_graph: showing 3 nodes, 1 topic')
            wait_for(lambda: (self.screen() != before).any(axis=2).sum() > DARK_MIN_PX,
                     GRAPH_DEADLINE_S, 'the window to draw talker2')
        finally:
            talker2.interrupt()
            talker2.wait_exit(EXIT_DEADLINE_S)
        self.wait_line('rqt_graph: showing 2 nodes, 1 topic', times=2)

        self.tool.interrupt()  # Ctrl-C in the terminal closes the window
        self.assertEqual(self.tool.wait_exit(EXIT_DEADLINE_S), 0, self.tool.output())
        self.assertNotIn('Traceback', self.tool.output())


if __name__ == '__main__':
    rostest.rosrun(PKG, 'graph_gui', TestGraphGui)
