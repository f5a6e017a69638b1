#!/usr/bin/env python3
"""Integration test of Lab 2's four commands: `rosrun beginner_tutorials talker`, `listener`,
`talker.py` and `listener.py`, run as printed, and two talker.py side by side."""
import os
import re
import subprocess
import sys
import time
import unittest

import rospkg
import rospy
import rostest
from course_common.testing import wait_for
from rosgraph_msgs.msg import Log

# chat_pkg's rostest helpers (recorder of /chatter and /rosout, Ctrl-C, counts), reused: the
# C++ talker and listener of the lab are chat_pkg's nodes.
sys.path.insert(0, os.path.join(rospkg.RosPack().get_path('chat_pkg'), 'test'))
from test_chat_node import (
    START_DEADLINE_S,
    Recorder,
    consecutive,
    counts,
    publishers_of,
    stop,
    subscribers_of,
)

PKG = 'beginner_tutorials'
MESSAGES_WANTED = 20  # two seconds at 10 Hz: enough to see an order
SIDE_BY_SIDE_WANTED = 10  # messages each of two talker.py sends while the other runs
TEXT = re.compile(r'^hello world (\d+)$')  # talker: the lab's "hello world " << count
HEARD = re.compile(r'^I heard: \[hello world (\d+)\]$')  # listener: "I heard: [%s]"
TIME_TEXT = re.compile(r'^hello world (\d+\.\d+)$')  # talker.py: "hello world %s" % get_time()
SCREEN = re.compile(r'^\[INFO\] \[[\d.]+\]: (.*)$')  # rospy's INFO line on the terminal
SAME_NAME = 'new node registered with same name'  # the master shutting an older node down


class InfoRecorder(Recorder):
    """chat_pkg's Recorder keeping only the INFO lines of /rosout: the nodes' own lines, not
    rospy's warnings and errors (a peer that drops a connection under load logs one)."""

    def _on_log(self, msg):
        if msg.level == Log.INFO:
            super()._on_log(msg)


def rosrun(exe):
    """`rosrun beginner_tutorials EXE`, as the lab types it, its screen lines captured."""
    return subprocess.Popen(['rosrun', PKG, exe], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=dict(os.environ))


def screen(output):
    """The texts of the INFO lines in a node's terminal output, in order."""
    return [m.group(1) for m in map(SCREEN.match, output.splitlines()) if m]


def times(texts):
    """The times in talker.py's texts (fails on a text that is not "hello world <time>")."""
    found = []
    for text in texts:
        match = TIME_TEXT.match(text)
        if not match:
            raise AssertionError('unexpected text %r (expected %s)' % (text, TIME_TEXT.pattern))
        found.append(float(match.group(1)))
    return found


def running(proc, what):
    """Fails at once, with the node's output, when proc has exited: waiting cannot help."""
    if proc.poll() is not None:
        raise AssertionError('%s exited (code %s): %s' % (what, proc.returncode,
                                                           proc.communicate()[0]))
    return True


def anonymous_name(proc, base, nodes_of):
    """Waits for the node of proc, named by anonymous=True `/<base>_<pid>_<ms>`, in nodes_of()."""
    pattern = re.compile(r'^/%s_%d_\d+$' % (base, proc.pid))

    def found():
        running(proc, base)
        return next((n for n in nodes_of('/chatter') if pattern.match(n)), None)
    return wait_for(found, START_DEADLINE_S, 'the anonymous %s of pid %d on /chatter'
                    % (base, proc.pid))


class TestTutorials(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_tutorials')
        cls.rec = InfoRecorder()

    def tearDown(self):
        # Each test stops its nodes: the next one starts with nobody on /chatter.
        wait_for(lambda: not publishers_of('/chatter'), START_DEADLINE_S,
                 'every talker to leave /chatter')

    def _wait_chatter(self, proc, node, n):
        wait_for(lambda: running(proc, node) and len(self.rec.chatter(node)) >= n,
                 START_DEADLINE_S, '%d messages from %s on /chatter' % (n, node))

    def _wait_logs(self, proc, node, n):
        wait_for(lambda: running(proc, node) and len(self.rec.logs(node)) >= n,
                 START_DEADLINE_S, '%d lines of %s on /rosout' % (n, node))

    def test_1_talker_and_listener(self):
        talker, listener = rosrun('talker'), rosrun('listener')
        try:
            self._wait_chatter(talker, '/talker', MESSAGES_WANTED)
            self.assertIn('/listener', subscribers_of('/chatter'))
            self._wait_logs(listener, '/listener', MESSAGES_WANTED)
        finally:
            (talker_code, talker_out), (listener_code, listener_out) = stop(talker), stop(listener)
        self.assertEqual(talker_code, 0, talker_out)
        self.assertEqual(listener_code, 0, listener_out)
        # The talker's counts arrive in order on /chatter (its first may go before we connect).
        self.assertTrue(consecutive(counts(self.rec.chatter('/talker'), TEXT)))
        # Its terminal shows every count from 0, as the lab's screen does.
        said = counts(screen(talker_out), TEXT)
        self.assertEqual(said, list(range(len(said))), talker_out)
        # The listener hears consecutive counts the talker said, on /rosout and on its terminal.
        for heard in (counts(self.rec.logs('/listener'), HEARD),
                      counts(screen(listener_out), HEARD)):
            self.assertTrue(consecutive(heard), heard)
            self.assertLessEqual(set(heard), set(said), 'heard a count never said')

    def test_2_talker_py_and_listener_py(self):
        started = time.time()
        talker, listener = rosrun('talker.py'), rosrun('listener.py')
        try:
            talker_name = anonymous_name(talker, 'talker', publishers_of)
            listener_name = anonymous_name(listener, 'listener', subscribers_of)
            self._wait_chatter(talker, talker_name, MESSAGES_WANTED)
            self._wait_logs(listener, listener_name, MESSAGES_WANTED)
            waited = time.time()
        finally:
            (talker_code, talker_out), (listener_code, listener_out) = stop(talker), stop(listener)
        self.assertEqual(talker_code, 0, talker_out)
        self.assertEqual(listener_code, 0, listener_out)
        # "hello world <rospy.get_time()>": times of this run, increasing, none left out of
        # the terminal's lines (rate is not asserted: timing goes in benchmarks).
        sent = self.rec.chatter(talker_name)
        stamps = times(sent)
        self.assertTrue(all(a < b for a, b in zip(stamps, stamps[1:], strict=False)), stamps)
        self.assertTrue(started <= stamps[0] and stamps[-1] <= waited, (started, stamps, waited))
        said = screen(talker_out)
        times(said)
        self.assertLessEqual(set(sent), set(said), talker_out)
        # The listener prefixes its own caller id, with no space: "/listener_<pid>_<ms>I heard".
        for lines in (self.rec.logs(listener_name), screen(listener_out)):
            self.assertTrue(lines, listener_out)
            for line in lines:
                self.assertTrue(line.startswith(listener_name + 'I heard hello world '), line)
                self.assertIn(line[len(listener_name + 'I heard '):], said, line)

    def test_3_two_talker_py_side_by_side(self):
        first = rosrun('talker.py')
        second = None
        try:
            first_name = anonymous_name(first, 'talker', publishers_of)
            self._wait_chatter(first, first_name, 1)
            second = rosrun('talker.py')
            second_name = anonymous_name(second, 'talker', publishers_of)
            self._wait_chatter(second, second_name, SIDE_BY_SIDE_WANTED)
            # The first keeps talking now that the second runs too: no name clash.
            self._wait_chatter(first, first_name,
                               len(self.rec.chatter(first_name)) + SIDE_BY_SIDE_WANTED)
            self.assertLessEqual({first_name, second_name}, publishers_of('/chatter'))
        finally:
            first_code, first_out = stop(first)
            second_code, second_out = stop(second) if second is not None else (None, '')
        for name, code, output in ((first_name, first_code, first_out),
                                   (second_name, second_code, second_out)):
            self.assertEqual(code, 0, output)
            self.assertNotIn(SAME_NAME, output)
            self.assertNotIn('Traceback', output)
            stamps = times(self.rec.chatter(name))
            self.assertTrue(all(a < b for a, b in zip(stamps, stamps[1:], strict=False)), name)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'tutorials', TestTutorials)
