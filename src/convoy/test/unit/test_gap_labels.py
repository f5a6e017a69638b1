"""Unit tests of convoy.gap_labels: the convoy's links and the gap labels rviz shows."""

import math

import pytest
from convoy.gap_labels import GapLabel, chain_links, gap_label

TOL = 1e-12


@pytest.mark.parametrize('robots, links', [
    (['robot1', 'robot2'], [('robot2', 'robot1')]),
    (['robot1', 'robot2', 'robot3'], [('robot2', 'robot1'), ('robot3', 'robot2')]),
    (('a', 'c', 'b'), [('c', 'a'), ('b', 'c')]),
])
def test_chain_links(robots, links):
    assert chain_links(robots) == links


@pytest.mark.parametrize('robots, message', [
    ([], '2 or more'), (['robot1'], '2 or more'), ('robot1 robot2', '2 or more'),
    (None, '2 or more'), (['robot1', ''], 'non-empty'), (['robot1', 3], 'non-empty'),
    (['robot1', 'robot2', 'robot1'], 'twice'),
])
def test_chain_links_rejects(robots, message):
    with pytest.raises(ValueError, match=message):
        chain_links(robots)


@pytest.mark.parametrize('f_xy, l_xy, gap, mid', [
    ((0.0, 0.0), (3.0, 4.0), 5.0, (1.5, 2.0)),
    ((5.544445, 5.544445), (5.544445, 5.544445), 0.0, (5.544445, 5.544445)),
    ((1, 1), (1, 2.5), 1.5, (1.0, 1.75)),
])
def test_gap_label(f_xy, l_xy, gap, mid):
    label = gap_label('robot2', 'robot1', f_xy, l_xy)
    assert isinstance(label, GapLabel)
    assert (label.follower, label.leader) == ('robot2', 'robot1')
    assert label.gap_m == pytest.approx(gap, abs=TOL)
    assert (label.mid_x, label.mid_y) == pytest.approx(mid, abs=TOL)
    assert label.text == 'robot2 -> robot1 %.2f m' % gap


@pytest.mark.parametrize('f_xy, l_xy', [
    ((math.nan, 0.0), (1.0, 1.0)), ((0.0, 0.0), (math.inf, 1.0)), ((0.0,), (1.0, 1.0)),
    ((0.0, None), (1.0, 1.0)),
])
def test_gap_label_rejects_bad_positions(f_xy, l_xy):
    with pytest.raises(ValueError, match='must be finite'):
        gap_label('robot2', 'robot1', f_xy, l_xy)
