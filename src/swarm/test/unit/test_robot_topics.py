"""robot_topics: stageros's names and counting robots on the master; spread."""
import pytest
from swarm.spread import spread_m

from swarm import robot_topics


@pytest.mark.parametrize('index, count, scan, cmd', [
    (0, 1, 'base_scan', 'cmd_vel'),                 # one robot: relative names
    (0, 2, '/robot_0/base_scan', '/robot_0/cmd_vel'),
    (999, 1000, '/robot_999/base_scan', '/robot_999/cmd_vel'),
])
def test_topics_are_stageros_names(index, count, scan, cmd):
    t = robot_topics.robot_topics(index, count)
    assert (t.scan, t.cmd_vel) == (scan, cmd)
    assert t.odom == scan.replace('base_scan', 'odom')


@pytest.mark.parametrize('index, count', [(-1, 3), (3, 3), (0, 0)])
def test_not_a_robot(index, count):
    with pytest.raises(ValueError, match='not a robot'):
        robot_topics.robot_topics(index, count)


def test_scan_robots_and_the_missing_ones():
    names = ['/clock', '/robot_2/base_scan', '/robot_0/base_scan', '/robot_0/odom',
             '/robot_10/base_scan', '/robot_x/base_scan', '/robot_3/base_scan_0']
    found = robot_topics.scan_robots(names)
    assert found == [0, 2, 10]
    assert robot_topics.missing_robots(found, range(4)) == [1, 3]
    assert robot_topics.first_few(list(range(8)), shown=2) == 'robot_0, robot_1, ... (8 in all)'


def test_spread():
    assert spread_m([(0.0, 0.0), (2.0, 0.0)]) == pytest.approx(1.0)
    assert spread_m([(1.0, 1.0)]) == 0.0
    with pytest.raises(ValueError):
        spread_m([])



@pytest.mark.parametrize('first, robots, world, ids', [
    (0, 0, 4, range(0, 4)),          # every robot
    (3, 0, 10, range(3, 10)),        # the rest of the world from robot_3
    (500, 500, None, range(500, 1000)),  # told: the world is not asked
    (2, 5, 3, range(2, 7)),          # told more than there are: the node warns, drives them
])
def test_driven_robots(first, robots, world, ids):
    assert robot_topics.driven_robots(first, robots, world) == ids


def test_first_past_the_world():
    with pytest.raises(ValueError, match='~first is 7 but stageros has 3 robots'):
        robot_topics.driven_robots(7, 0, 3)
