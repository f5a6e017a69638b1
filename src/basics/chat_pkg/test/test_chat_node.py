#!/usr/bin/env python3
"""Integration test of chat.launch and the slide's two renamed talkers (__name:=talker1/2)."""
import re
import unittest

import rospy
import rostest
from course_common.testing import consecutive, info_texts, spawn, wait_for
from course_common.testing import numbers_in as counts
from course_common.testing.master import publishers_of, services_of, subscribers_of
from course_common.testing.recorders import LogRecorder, Recorder
from rosgraph_msgs.msg import Log
from std_msgs.msg import String

PKG = 'chat_pkg'
START_DEADLINE_S = 30.0  # rosrun + rospy start-up on a loaded 2-core machine
EXIT_DEADLINE_S = 30.0  # Ctrl-C to exit, for a node that may be mid-registration under load
MESSAGES_WANTED = 20  # two seconds at 10 Hz: enough to see an order
TEXT = re.compile(r'^hello world (\d+)$')  # the slide's "hello world " << count
HEARD = re.compile(r'^I heard: \[hello world (\d+)\]$')  # the slide's "I heard: [%s]"


def rosrun_talker(name):
    """`rosrun chat_pkg talker __name:=NAME`, its screen lines read as they come."""
    return spawn(['rosrun', PKG, 'talker', '__name:=' + name], stop_timeout_s=EXIT_DEADLINE_S)


def screen_counts(talker):
    """The counts a talker logged on its screen so far."""
    return [int(m.group(1)) for m in map(TEXT.match, info_texts(talker.lines())) if m]


def stop(talker):
    """Ctrl-C; (exit code, output), the code None if it had to be killed."""
    return talker.stop(), talker.output()


class TestChat(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_chat')
        cls.chatter = Recorder('/chatter', String, queue_size=1000)
        cls.rosout = LogRecorder(connect=False)

    def setUp(self):
        # Every test starts from chat.launch alone, in any order: the talkers an earlier test
        # started unregister in the background after their exit.
        wait_for(lambda: publishers_of('/chatter') == {'/talker'}, EXIT_DEADLINE_S,
                 "chat.launch's /talker alone on /chatter before the test")

    def _wait_messages(self, node, n=MESSAGES_WANTED):
        wait_for(lambda: len(self.chatter.data(node)) >= n, START_DEADLINE_S,
                 '%d messages from %s on /chatter' % (n, node))
        return counts(self.chatter.data(node), TEXT)

    def test_talker_counts_arrive_in_order(self):
        heard = self._wait_messages('/talker')
        self.assertTrue(consecutive(heard), heard)
        # The talker logs each text it publishes, with the same count.
        logged = counts(self.rosout.lines(node='/talker'), TEXT)
        self.assertTrue(consecutive(logged), logged)
        self.assertTrue(set(heard) & set(logged), (heard, logged))

    def test_listener_logs_what_it_hears(self):
        self.assertEqual(publishers_of('/chatter'), {'/talker'})
        # The launch starts both at once: on a loaded machine the listener may register last.
        wait_for(lambda: '/listener' in subscribers_of('/chatter'), START_DEADLINE_S,
                 "chat.launch's /listener subscribed to /chatter")
        # The listener's lines from here on: /talker is alone on /chatter (setUp), so none is
        # about a message of another test's talker (those exited before they unregistered).
        # Its INFO lines: rospy itself may WARN on the listener's behalf about a peer that hung
        # up before its handshake (a /rosout subscriber's duplicate connection as they start).
        def info_lines():
            return self.rosout.lines(level=Log.INFO, node='/listener')
        start = len(info_lines())
        wait_for(lambda: len(info_lines()) >= start + MESSAGES_WANTED,
                 START_DEADLINE_S, '%d "I heard" lines of /listener on /rosout' % MESSAGES_WANTED)
        heard = counts(info_lines()[start:], HEARD)
        self.assertTrue(consecutive(heard), heard)
        # the talker's line of a count and the listener's reach /rosout from two nodes, in
        # either order: wait for the talker's line of the last count heard (a count never
        # sent never gets one)
        wait_for(lambda: max(heard) in counts(self.rosout.lines(node='/talker'), TEXT),
                 START_DEADLINE_S, "the talker's line of count %d" % max(heard))
        talked = counts(self.rosout.lines(node='/talker'), TEXT)
        self.assertLessEqual(set(heard), set(range(max(talked) + 1)), 'heard a count never sent')

    def test_two_renamed_talkers_both_publish(self):
        talkers = {name: rosrun_talker(name) for name in ('talker1', 'talker2')}
        try:
            for name in talkers:
                heard = self._wait_messages('/' + name)
                self.assertTrue(consecutive(heard), (name, heard))
            self.assertEqual(publishers_of('/chatter'), {'/talker', '/talker1', '/talker2'})
            self.assertTrue(consecutive(counts(self.chatter.data('/talker'), TEXT)))
        finally:
            results = {name: stop(proc) for name, proc in talkers.items()}
        for name, (code, output) in results.items():
            self.assertEqual(code, 0, output)
            self.assertIn('hello world 0', output, name)
        wait_for(lambda: publishers_of('/chatter') == {'/talker'}, EXIT_DEADLINE_S,
                 'talker1 and talker2 to leave /chatter')

    def test_same_name_twice_the_older_exits(self):
        # The slide: "If the same node is launched twice, roscore directs the older node to exit".
        # rospy asks the master for /rosout_disable_topics_generation on every log line while
        # that parameter is unset, and each ask re-registers the node's URI: the older talker's
        # next line after the newer one registered would then make the master shut the NEWER
        # one down too. The workspace's master sets it (course_common's roscore.xml), and the
        # talker asks once (course_common.startup); see README.
        older = rosrun_talker('talker_twin')
        newer = None
        try:
            self._wait_messages('/talker_twin', 1)
            # Start the second only once the first is fully registered, as when a student types
            # the command again: rospy registers a node's logger services in a background thread,
            # and a late registration of the older one would shut the newer one down instead.
            wait_for(lambda: {'/talker_twin/get_loggers', '/talker_twin/set_logger_level'}
                     <= services_of('/talker_twin'), START_DEADLINE_S,
                     'the older talker_twin fully registered (its logger services)')
            newer = rosrun_talker('talker_twin')
            wait_for(older.exited, START_DEADLINE_S,
                     'the older talker_twin to exit')
            # The newer one is the registered /talker_twin and keeps talking. (Whether a
            # subscriber that was connected to the older one hears the newer is up to rospy's
            # reconnection, not to the talker: under load this test's subscriber missed it.)
            wait_for(lambda: '/talker_twin' in publishers_of('/chatter'), START_DEADLINE_S,
                     'the newer talker_twin registered on /chatter (its lines: %r)'
                     % newer.lines())
            since = len(screen_counts(newer))
            wait_for(lambda: len(screen_counts(newer)) >= since + 5, START_DEADLINE_S,
                     '5 more lines of the newer talker_twin after the older exited')
        finally:
            code, output = stop(older)
            newer_code, newer_output = stop(newer) if newer is not None else (None, '')
        self.assertIn('new node registered with same name', output)
        self.assertNotIn('Traceback', output)
        self.assertEqual(newer_code, 0, newer_output)
        self.assertNotIn('new node registered with same name', newer_output)
        newer_counts = screen_counts(newer)
        self.assertTrue(consecutive(newer_counts) and newer_counts[0] == 0, newer_output)

if __name__ == '__main__':
    rostest.rosrun(PKG, 'chat', TestChat)
