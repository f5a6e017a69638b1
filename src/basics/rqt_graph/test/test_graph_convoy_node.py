#!/usr/bin/env python3
"""rqt_graph on the course's convoy.launch: the nodes, topics and edges a student expects."""
import os
import shutil

import rostest
from course_common.testing import ScratchDirTestCase, results_dir
from graph_support import png_size, rqt_graph, wait_graph
from PIL import Image

PKG = 'rqt_graph'
# Once the two `rosservice call --wait /spawn` helpers are done, three nodes stay.
NODES = {'/turtlesim', '/convoy_node', '/convoy2_node'}
# The simulator publishes every robot's pose and colour sensor and subscribes its cmd_vel;
# each convoy_node reads its leader's and follower's poses and drives the follower.
EDGES = {
    ('/turtlesim', '/robot1/pose'), ('/turtlesim', '/robot2/pose'),
    ('/turtlesim', '/robot3/pose'),
    ('/turtlesim', '/robot1/color_sensor'), ('/turtlesim', '/robot2/color_sensor'),
    ('/turtlesim', '/robot3/color_sensor'),
    ('/robot1/cmd_vel', '/turtlesim'), ('/robot2/cmd_vel', '/turtlesim'),
    ('/robot3/cmd_vel', '/turtlesim'),
    ('/robot1/pose', '/convoy_node'), ('/robot2/pose', '/convoy_node'),
    ('/convoy_node', '/robot2/cmd_vel'),
    ('/robot2/pose', '/convoy2_node'), ('/robot3/pose', '/convoy2_node'),
    ('/convoy2_node', '/robot3/cmd_vel'),
}
TOPICS = {'/robot%d/%s' % (i, t) for i in (1, 2, 3) for t in ('pose', 'cmd_vel', 'color_sensor')}


def is_convoy(graph):
    return graph.nodes == NODES and graph.edges == EDGES


class TestGraphConvoy(ScratchDirTestCase):
    TMP_PREFIX = 'rqt_graph_convoy_'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.graph = wait_graph(os.path.join(cls.tmp, 'convoy.dot'), is_convoy,
                               'the convoy graph: turtlesim, convoy_node, convoy2_node')

    def test_nodes_topics_edges(self):
        self.assertEqual(self.graph.topics, TOPICS)
        self.assertEqual(self.graph.others, set())
        for name in self.graph.nodes | self.graph.topics:
            self.assertFalse(name.startswith(('/turtle1', '/rosout')), name)
        # The convoy's chain, read along the arrows: robot1 leads robot2, robot2 leads robot3.
        self.assertIn(('/robot1/pose', '/convoy_node'), self.graph.edges)
        self.assertIn(('/convoy_node', '/robot2/cmd_vel'), self.graph.edges)
        self.assertIn(('/convoy2_node', '/robot3/cmd_vel'), self.graph.edges)
        self.assertNotIn(('/convoy_node', '/robot1/cmd_vel'), self.graph.edges)

    def test_namespace_boxes(self):
        with open(os.path.join(self.tmp, 'convoy.dot')) as dot:
            text = dot.read()
        for robot in ('robot1', 'robot2', 'robot3'):
            self.assertIn('subgraph cluster_%s' % robot, text)

    def test_hide_leaf_topics(self):
        path = os.path.join(self.tmp, 'leaf.dot')
        graph = wait_graph(path, lambda g: g.nodes == NODES, 'the convoy graph, leaves hidden',
                           '--hide-leaf-topics')
        # robot1 is driven by nobody (the keyboard is not running); colour sensors are unread.
        self.assertEqual(graph.topics, {'/robot1/pose', '/robot2/pose', '/robot3/pose',
                                        '/robot2/cmd_vel', '/robot3/cmd_vel'})

    def test_png(self):
        path = os.path.join(self.tmp, 'convoy.png')
        code, out, err = rqt_graph('--out', path)
        self.assertEqual(code, 0, err)
        self.assertIn('(3 nodes, 9 topics)', out)
        width, height = png_size(path)
        self.assertGreater(width * height, 200 * 200)
        with Image.open(path) as image:
            image.verify()
        shutil.copy(path, os.path.join(results_dir(), 'rqt_graph_convoy.png'))


if __name__ == '__main__':
    rostest.rosrun(PKG, 'graph_convoy', TestGraphConvoy)
