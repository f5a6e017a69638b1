#!/usr/bin/env python3
"""Integration test of `rosrun first_pkg hello`: its counted lines, on screen and on /rosout."""
import os
import re
import signal
import subprocess
import threading
import unittest

import rospy
import rostest
from course_common.testing import wait_for
from rosgraph_msgs.msg import Log

PKG = 'first_pkg'
START_DEADLINE_S = 30.0  # rosrun + rospy start-up on a loaded 2-core machine
LINES_WANTED = 20  # two seconds of lines at 10 Hz: enough to see an order
EXIT_DEADLINE_S = 15.0
LINE = re.compile(r'^hello world (\d+)$')  # as the decks' screens show it
SCREEN_LINE = re.compile(r'^\[INFO\] \[[\d.]+\]: (hello world \d+)$')


def counts(lines):
    """The counts of the lines that read `hello world <count>`, in order; fails on any other."""
    found = []
    for line in lines:
        match = LINE.match(line)
        if not match:
            raise AssertionError('unexpected hello line %r' % line)
        found.append(int(match.group(1)))
    return found


class TestHello(unittest.TestCase):
    def setUp(self):
        self._lock = threading.Lock()
        self._rosout = []

    def _on_log(self, msg):
        with self._lock:
            self._rosout.append(msg)

    def _hello_lines(self, name):
        with self._lock:
            return [m.msg for m in self._rosout if m.name == name]

    def _run(self, *args):
        """Runs `rosrun first_pkg hello ARGS` until LINES_WANTED lines reached /rosout."""
        name = '/' + next((a.split(':=')[1] for a in args if a.startswith('__name:=')),
                          'hello')
        proc = subprocess.Popen(['rosrun', PKG, 'hello'] + list(args), stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, env=dict(os.environ))
        try:
            wait_for(lambda: len(self._hello_lines(name)) >= LINES_WANTED, START_DEADLINE_S,
                     '%d lines of %s on /rosout' % (LINES_WANTED, name))
        finally:
            proc.send_signal(signal.SIGINT)
            output, _ = proc.communicate(timeout=EXIT_DEADLINE_S)
        return proc.returncode, output, self._hello_lines(name)

    def test_counts_in_order_on_screen_and_rosout(self):
        sub = rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)
        self.addCleanup(sub.unregister)
        code, output, rosout = self._run()
        self.assertEqual(code, 0, output)
        self.assertNotIn('Traceback', output)
        screen = [m.group(1) for m in map(SCREEN_LINE.match, output.splitlines()) if m]
        on_screen = counts(screen)
        # The screen shows every line from the first: 0, 1, 2, ... with none missing.
        self.assertGreaterEqual(len(on_screen), LINES_WANTED, output)
        self.assertEqual(on_screen, list(range(len(on_screen))), output)
        # /rosout may miss the first lines (sent before our subscription connected), never
        # one in the middle, and never out of order.
        heard = counts(rosout)
        self.assertEqual(heard, list(range(heard[0], heard[0] + len(heard))), heard)
        self.assertLessEqual(heard[-1], on_screen[-1])

    def test_renamed_hello_logs_under_its_name(self):
        sub = rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)
        self.addCleanup(sub.unregister)
        code, output, rosout = self._run('__name:=hello_again')
        self.assertEqual(code, 0, output)
        heard = counts(rosout)
        self.assertEqual(heard, list(range(heard[0], heard[0] + len(heard))), heard)
        self.assertEqual(self._hello_lines('/hello'), [], 'lines under the default name')


if __name__ == '__main__':
    rospy.init_node('test_hello')  # rostest renames it hello_lines: not /hello
    rostest.rosrun(PKG, 'hello_lines', TestHello)
