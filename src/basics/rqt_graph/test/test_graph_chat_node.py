#!/usr/bin/env python3
"""rqt_graph on chat.launch: the DOT, PNG and SVG it writes, nodes coming and going, errors."""
import os
import shutil
import tempfile

import rostest
from course_common.testing import ScratchDirTestCase, results_dir, spawn
from graph_support import png_size, rqt_graph, wait_graph
from PIL import Image

PKG = 'rqt_graph'
EXIT_DEADLINE_S = 30.0  # Ctrl-C to exit, for a node that may be mid-registration under load
CHAT_NODES = {'/talker', '/listener'}
CHAT_EDGES = {('/talker', '/chatter'), ('/chatter', '/listener')}


def is_chat(graph):
    return graph.nodes == CHAT_NODES and graph.edges == CHAT_EDGES


class TestGraphChat(ScratchDirTestCase):
    """Each test that reads the graph first waits for chat.launch's graph (a node another test
    started leaves it in the background), so they run in any order."""

    TMP_PREFIX = 'rqt_graph_chat_'

    def test_talker_chatter_listener(self):
        graph = wait_graph(self.path('chat.dot'), is_chat, 'talker -> /chatter -> listener')
        self.assertEqual(graph.topics, {'/chatter'})
        self.assertEqual(graph.others, set())
        with open(self.path('chat.dot')) as dot:
            self.assertNotIn('rosout', dot.read())

    def test_rosout_hidden_unless_all(self):
        wait_graph(self.path('before.dot'), is_chat, 'the chat graph')
        # rostest starts no rosout node; roscore does: start one, as roscore would.
        rosout = spawn(['rosrun', 'rosout', 'rosout'])
        self.addCleanup(rosout.stop)
        try:
            graph = wait_graph(self.path('all.dot'), lambda g: '/rosout' in g.nodes,
                               'the /rosout node with --all', '--all')
            self.assertEqual(graph.nodes, CHAT_NODES | {'/rosout'})
            self.assertEqual(graph.topics, {'/chatter', '/rosout', '/rosout_agg'})
            self.assertTrue(CHAT_EDGES | {('/talker', '/rosout'), ('/listener', '/rosout'),
                                          ('/rosout', '/rosout'), ('/rosout', '/rosout_agg')}
                            <= graph.edges, graph)
            wait_graph(self.path('quiet.dot'), is_chat, 'the chat graph without /rosout')
        finally:
            rosout.interrupt()
            rosout.wait_exit(EXIT_DEADLINE_S)

    def test_png_and_svg(self):
        wait_graph(self.path('wait.dot'), is_chat, 'the chat graph')
        code, out, err = rqt_graph('--out', self.path('chat.png'))
        self.assertEqual(code, 0, err)
        self.assertIn('wrote %s (2 nodes, 1 topic)' % self.path('chat.png'), out)
        width, height = png_size(self.path('chat.png'))
        self.assertGreater(width, height)  # left to right: talker, /chatter, listener
        with Image.open(self.path('chat.png')) as image:
            image.verify()  # every chunk's CRC and the end of the stream
        shutil.copy(self.path('chat.png'), os.path.join(results_dir(), 'rqt_graph_chat.png'))
        code, _, err = rqt_graph('--out', self.path('chat.svg'))
        self.assertEqual(code, 0, err)
        with open(self.path('chat.svg')) as svg:
            text = svg.read()
        self.assertIn('<svg', text)
        for label in ('/talker', '/chatter', '/listener', 'std_msgs/String'):
            self.assertIn(label, text)

    def test_nodes_come_and_go(self):
        wait_graph(self.path('before.dot'), is_chat, 'the chat graph')
        talker2 = spawn(['rosrun', 'chat_pkg', 'talker', '__name:=talker2'])
        self.addCleanup(talker2.stop)
        try:
            wait_graph(self.path('two.dot'),
                       lambda g: g.nodes == CHAT_NODES | {'/talker2'}
                       and g.edges == CHAT_EDGES | {('/talker2', '/chatter')},
                       'talker2 -> /chatter in the graph')
        finally:
            talker2.interrupt()
            talker2.wait_exit(EXIT_DEADLINE_S)
        wait_graph(self.path('one.dot'), is_chat, 'talker2 gone from the graph')

    def test_no_display_writes_png_in_cwd(self):
        env = {k: v for k, v in os.environ.items() if k != 'DISPLAY'}
        cwd = tempfile.mkdtemp(dir=self.tmp)
        code, out, err = rqt_graph(env=env, cwd=cwd)
        self.assertEqual(code, 0, err)
        self.assertIn('no window (DISPLAY is not set): writing rqt_graph.png instead', out)
        self.assertGreater(png_size(os.path.join(cwd, 'rqt_graph.png'))[0], 0)

    def test_clear_errors(self):
        # (name, args, environment change, exit code, words of the one-line error)
        cases = [
            ('no master', ['--out', self.path('x.png')],
             {'ROS_MASTER_URI': 'http://localhost:1/'}, 1,
             ['cannot reach the ROS master at http://localhost:1/ (ROS_MASTER_URI)']),
            ('bad extension', ['--out', self.path('x.jpg')], {}, 2,
             ["unknown output extension '.jpg'", '.dot, .png, .svg']),
            ('unwritable', ['--out', '/nonexistent-dir/x.png'], {}, 1,
             ['cannot write /nonexistent-dir/x.png']),
            ('unknown option', ['--colour'], {}, 2, ['unrecognized arguments: --colour']),
        ]
        for name, args, env_change, want_code, words in cases:
            with self.subTest(name=name):
                code, out, err = rqt_graph(*args, env=dict(os.environ, **env_change))
                self.assertEqual(code, want_code, out + err)
                self.assertNotIn('Traceback', err)
                last = err.strip().splitlines()[-1]
                for word in words:
                    self.assertIn(word, last)
        self.assertFalse(os.path.exists(self.path('x.png')))


if __name__ == '__main__':
    rostest.rosrun(PKG, 'graph_chat', TestGraphChat)
