#!/usr/bin/env python3
"""Integration test of Lab 2's four commands: `rosrun beginner_tutorials talker`, `listener`,
`talker.py` and `listener.py`, run as printed, and two talker.py side by side."""
import re
import time
import unittest

import rospy
import rostest
from course_common.testing import consecutive, info_texts, spawn, wait_for
from course_common.testing import numbers_in as counts
from course_common.testing.master import publishers_of, subscribers_of
from course_common.testing.recorders import LogRecorder, Recorder
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

PKG = 'beginner_tutorials'
START_DEADLINE_S = 30.0  # rosrun + rospy start-up on a loaded 2-core machine
EXIT_DEADLINE_S = 30.0  # Ctrl-C to exit, for a node that may be mid-registration under load
MESSAGES_WANTED = 20  # two seconds at 10 Hz: enough to see an order
SIDE_BY_SIDE_WANTED = 10  # messages each of two talker.py sends while the other runs
TEXT = re.compile(r'^hello world (\d+)$')  # talker: the lab's "hello world " << count
HEARD = re.compile(r'^I heard: \[hello world (\d+)\]$')  # listener: "I heard: [%s]"
TIME_TEXT = re.compile(r'^hello world (\d+\.\d+)$')  # talker.py: "hello world %s" % get_time()
SAME_NAME = 'new node registered with same name'  # the master shutting an older node down


def rosrun(exe):
    """`rosrun beginner_tutorials EXE`, as the lab types it, its screen lines captured."""
    return spawn(['rosrun', PKG, exe], stop_timeout_s=EXIT_DEADLINE_S)


def stop(proc):
    """Ctrl-C; (exit code, screen output), the code None if it had to be killed."""
    return proc.stop(), proc.output()


def screen(output):
    """The texts of the INFO lines in a node's terminal output, in order."""
    return info_texts(output.splitlines())


def times(texts):
    """The times in talker.py's texts (fails on a text that is not "hello world <time>")."""
    return counts(texts, TIME_TEXT, float)


def running(proc, what):
    """Fails at once, with the node's output, when proc has exited: waiting cannot help."""
    if proc.exited():
        proc.wait_exit()  # and its last lines read
        raise AssertionError('%s exited (code %s): %s' % (what, proc.returncode, proc.output()))
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
        # The master is the workspace's (course_common's roscore.xml): it sets
        # /rosout_disable_topics_generation, without which a Ctrl-C during talker.py's log
        # line deadlocks rospy's shutdown (9 of 480 stops here; README).
        cls.chatter = Recorder('/chatter', String, queue_size=1000)
        # The nodes' own INFO lines only, not rospy's warnings and errors (a peer that drops
        # a connection under load logs one).
        cls.rosout = LogRecorder(accept=lambda m: m.level == Log.INFO, connect=False)

    def setUp(self):
        # Each test starts its own nodes, in any order: first, nobody on /chatter (a talker
        # of an earlier test unregisters in the background after its exit).
        wait_for(lambda: not publishers_of('/chatter'), START_DEADLINE_S,
                 'nobody on /chatter before the test (an earlier talker gone)')

    def _wait_chatter(self, proc, node, n):
        wait_for(lambda: running(proc, node) and len(self.chatter.data(node)) >= n,
                 START_DEADLINE_S, '%d messages from %s on /chatter' % (n, node))

    def _wait_logs(self, proc, node, n):
        wait_for(lambda: running(proc, node) and len(self.rosout.lines(node=node)) >= n,
                 START_DEADLINE_S, '%d lines of %s on /rosout' % (n, node))

    def test_talker_and_listener(self):
        talker, listener = rosrun('talker'), rosrun('listener')
        try:
            self._wait_chatter(talker, '/talker', MESSAGES_WANTED)
            # Started together with the talker, the listener may register after it.
            wait_for(lambda: '/listener' in subscribers_of('/chatter'), START_DEADLINE_S,
                     '/listener subscribed to /chatter')
            self._wait_logs(listener, '/listener', MESSAGES_WANTED)
        finally:
            (talker_code, talker_out), (listener_code, listener_out) = stop(talker), stop(listener)
        self.assertEqual(talker_code, 0, talker_out)
        self.assertEqual(listener_code, 0, listener_out)
        # The talker's counts arrive in order on /chatter (its first may go before we connect).
        self.assertTrue(consecutive(counts(self.chatter.data('/talker'), TEXT)))
        # Its terminal shows every count from 0, as the lab's screen does.
        said = counts(screen(talker_out), TEXT)
        self.assertEqual(said, list(range(len(said))), talker_out)
        # The listener hears consecutive counts the talker said, on /rosout and on its terminal.
        for heard in (counts(self.rosout.lines(node='/listener'), HEARD),
                      counts(screen(listener_out), HEARD)):
            self.assertTrue(consecutive(heard), heard)
            self.assertLessEqual(set(heard), set(said), 'heard a count never said')

    def test_talker_py_and_listener_py(self):
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
        sent = self.chatter.data(talker_name)
        stamps = times(sent)
        self.assertTrue(all(a < b for a, b in zip(stamps, stamps[1:], strict=False)), stamps)
        self.assertTrue(started <= stamps[0] and stamps[-1] <= waited, (started, stamps, waited))
        said = screen(talker_out)
        times(said)
        self.assertLessEqual(set(sent), set(said), talker_out)
        # The listener prefixes its own caller id, with no space: "/listener_<pid>_<ms>I heard".
        for lines in (self.rosout.lines(node=listener_name), screen(listener_out)):
            self.assertTrue(lines, listener_out)
            for line in lines:
                self.assertTrue(line.startswith(listener_name + 'I heard hello world '), line)
                self.assertIn(line[len(listener_name + 'I heard '):], said, line)

    def test_two_talker_py_side_by_side(self):
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
                               len(self.chatter.data(first_name)) + SIDE_BY_SIDE_WANTED)
            self.assertLessEqual({first_name, second_name}, publishers_of('/chatter'))
        finally:
            first_code, first_out = stop(first)
            second_code, second_out = stop(second) if second is not None else (None, '')
        for name, code, output in ((first_name, first_code, first_out),
                                   (second_name, second_code, second_out)):
            self.assertEqual(code, 0, output)
            self.assertNotIn(SAME_NAME, output)
            self.assertNotIn('Traceback', output)
            stamps = times(self.chatter.data(name))
            self.assertTrue(all(a < b for a, b in zip(stamps, stamps[1:], strict=False)), name)


if __name__ == '__main__':
    rostest.rosrun(PKG, 'tutorials', TestTutorials)
