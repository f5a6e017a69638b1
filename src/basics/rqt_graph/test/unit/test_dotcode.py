"""Unit tests of rqt_graph.dotcode: DOT of a graph, its read-back, the formats, rendering."""
import io

import pydot
import pytest
from PIL import Image
from rqt_graph.dotcode import build_dot, namespace, output_format, render
from rqt_graph.graph_model import graph_from_state

CONVOY_STATE = [
    [['/robot1/pose', ['/turtlesim']], ['/robot2/pose', ['/turtlesim']],
     ['/robot2/cmd_vel', ['/convoy_node']]],
    [['/robot1/pose', ['/convoy_node']], ['/robot2/pose', ['/convoy_node']],
     ['/robot1/cmd_vel', ['/turtlesim']], ['/robot2/cmd_vel', ['/turtlesim']]],
    [],
]


def read_back(text):
    """{label: shape} and {(label, label)} of a DOT text, clusters included."""
    (dot,) = pydot.graph_from_dot_data(text)
    ids, shapes = {}, {}
    graphs = [dot]
    while graphs:
        g = graphs.pop()
        graphs.extend(g.get_subgraphs())
        for node in g.get_nodes():
            label = node.get('label')
            if label:
                ids[node.get_name()] = label.strip('"')
                shapes[label.strip('"')] = node.get('shape')
    edges = {(ids[e.get_source()], ids[e.get_destination()]) for e in dot.get_edges()}
    return shapes, edges


@pytest.mark.parametrize('name, ns', [
    ('/talker', ''), ('/robot1/pose', '/robot1'), ('/a/b/c', '/a'), ('/', ''),
])
def test_namespace(name, ns):
    assert namespace(name) == ns


def test_convoy_dot_reads_back():
    text = build_dot(graph_from_state(CONVOY_STATE)).to_string()
    shapes, edges = read_back(text)
    assert shapes == {'/turtlesim': 'ellipse', '/convoy_node': 'ellipse', '/robot1/pose': 'box',
                      '/robot2/pose': 'box', '/robot1/cmd_vel': 'box', '/robot2/cmd_vel': 'box'}
    assert edges == {('/turtlesim', '/robot1/pose'), ('/turtlesim', '/robot2/pose'),
                     ('/convoy_node', '/robot2/cmd_vel'), ('/robot1/pose', '/convoy_node'),
                     ('/robot2/pose', '/convoy_node'), ('/robot1/cmd_vel', '/turtlesim'),
                     ('/robot2/cmd_vel', '/turtlesim')}
    assert 'subgraph cluster_robot1' in text and 'rankdir=LR' in text


def test_no_groups_no_clusters():
    text = build_dot(graph_from_state(CONVOY_STATE), clusters=False).to_string()
    assert 'subgraph' not in text
    assert len(read_back(text)[1]) == 7


def test_node_and_topic_of_one_name_stay_apart():
    g = graph_from_state([[['/echo', ['/echo']]], [], []])
    (dot,) = pydot.graph_from_dot_data(build_dot(g).to_string())
    assert sorted(n.get('shape') for n in dot.get_nodes() if n.get('label')) == ['box', 'ellipse']
    assert len(dot.get_edges()) == 1


def test_dot_is_deterministic():
    a = build_dot(graph_from_state(CONVOY_STATE)).to_string()
    b = build_dot(graph_from_state([list(reversed(c)) for c in CONVOY_STATE])).to_string()
    assert a == b


def test_empty_graph_says_so():
    assert 'no nodes' in build_dot(graph_from_state([[], [], []])).to_string()


@pytest.mark.parametrize('path, fmt', [
    ('x.png', 'png'), ('/tmp/a.b/X.SVG', 'svg'), ('graph.dot', 'dot'),
])
def test_output_format(path, fmt):
    assert output_format(path) == fmt


@pytest.mark.parametrize('path', ['x.jpg', 'x', 'x.png.txt', '.png'])
def test_output_format_rejects(path):
    with pytest.raises(ValueError, match='unknown output extension'):
        output_format(path)


def test_render_png_svg_dot():
    dot = build_dot(graph_from_state(CONVOY_STATE))
    png = render(dot, 'png')
    image = Image.open(io.BytesIO(png))
    assert image.format == 'PNG' and image.width > 200 and image.height > 100
    svg = render(dot, 'svg').decode()
    assert svg.lstrip().startswith('<?xml') and '/robot2/cmd_vel' in svg
    assert render(dot, 'dot').decode() == dot.to_string()


def test_render_rejects_unknown_format():
    with pytest.raises(ValueError, match='unknown format'):
        render(build_dot(graph_from_state([[], [], []])), 'jpg')
