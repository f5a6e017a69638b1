#!/usr/bin/env python3
"""Integration test of `rosrun first_pkg hello`: its counted lines, on screen and on /rosout."""
import re
import unittest

import rospy
import rostest
from course_common.testing import info_texts, numbers_in, spawn, wait_for
from course_common.testing.recorders import LogRecorder

PKG = 'first_pkg'
START_DEADLINE_S = 30.0  # rosrun + rospy start-up on a loaded 2-core machine
LINES_WANTED = 20  # two seconds of lines at 10 Hz: enough to see an order
EXIT_DEADLINE_S = 15.0
LINE = re.compile(r'^hello world (\d+)$')  # as the decks' screens show it


def counts(lines):
    """The counts of the lines that read `hello world <count>`, in order; fails on any other."""
    return numbers_in(lines, LINE)


class TestHello(unittest.TestCase):
    def setUp(self):
        self.rosout = LogRecorder(connect=False)
        self.addCleanup(self.rosout.close)

    def _run(self, *args):
        """Runs `rosrun first_pkg hello ARGS` until LINES_WANTED lines reached /rosout; returns
        (exit code after Ctrl-C, its screen output, its lines on /rosout)."""
        name = '/' + next((a.split(':=')[1] for a in args if a.startswith('__name:=')),
                          'hello')
        proc = spawn(['rosrun', PKG, 'hello'] + list(args), stop_timeout_s=EXIT_DEADLINE_S)
        try:
            wait_for(lambda: len(self.rosout.lines(node=name)) >= LINES_WANTED,
                     START_DEADLINE_S, '%d lines of %s on /rosout' % (LINES_WANTED, name))
        finally:
            code = proc.stop()
        return code, proc.output(), self.rosout.lines(node=name)

    def test_counts_in_order_on_screen_and_rosout(self):
        code, output, rosout = self._run()
        self.assertEqual(code, 0, output)
        self.assertNotIn('Traceback', output)
        on_screen = counts([t for t in info_texts(output.splitlines()) if LINE.match(t)])
        # The screen shows every line from the first: 0, 1, 2, ... with none missing.
        self.assertGreaterEqual(len(on_screen), LINES_WANTED, output)
        self.assertEqual(on_screen, list(range(len(on_screen))), output)
        # /rosout may miss the first lines (sent before our subscription connected), never
        # one in the middle, and never out of order.
        heard = counts(rosout)
        self.assertEqual(heard, list(range(heard[0], heard[0] + len(heard))), heard)
        self.assertLessEqual(heard[-1], on_screen[-1])

    def test_renamed_hello_logs_under_its_name(self):
        code, output, rosout = self._run('__name:=hello_again')
        self.assertEqual(code, 0, output)
        heard = counts(rosout)
        self.assertEqual(heard, list(range(heard[0], heard[0] + len(heard))), heard)
        self.assertEqual(self.rosout.lines(node='/hello'), [], 'lines under the default name')


if __name__ == '__main__':
    rospy.init_node('test_hello')  # rostest renames it hello_lines: not /hello
    rostest.rosrun(PKG, 'hello_lines', TestHello)
