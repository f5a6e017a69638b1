"""stageros's topic names for robot i of N (stage_ros 1.8.0's mapName), and finding N from
the master's topic list (pure, no rospy).

With more than one robot every name is absolute, ``/robot_<i>/base_scan``; with exactly one,
stageros's names are relative (``base_scan``), in the namespace both nodes share.
"""
import re
from dataclasses import dataclass

_SCAN = re.compile(r'^/robot_(\d+)/base_scan$')


@dataclass(frozen=True)
class RobotTopics:
    scan: str
    odom: str
    cmd_vel: str


def robot_topics(index, count):
    """RobotTopics of robot `index` (0-based) of `count`; ValueError if it is not one."""
    if count < 1 or not 0 <= index < count:
        raise ValueError('robot %d of %d is not a robot' % (index, count))
    p = '' if count == 1 else '/robot_%d/' % index
    return RobotTopics(p + 'base_scan', p + 'odom', p + 'cmd_vel')


def scan_robots(topic_names):
    """The sorted indices i of the /robot_<i>/base_scan topics among topic_names."""
    found = set()
    for name in topic_names:
        m = _SCAN.match(name)
        if m:
            found.add(int(m.group(1)))
    return sorted(found)


def missing_robots(indices, wanted):
    """The robots of `wanted` (an iterable of robot numbers, such as a range) that indices
    lacks, in wanted's order."""
    have = set(indices)
    return [i for i in wanted if i not in have]


def driven_robots(first, robots, world_count=None):
    """The robot numbers a node drives: ``robots`` of them from ``first``, or with ``robots``
    0 every robot of the world's ``world_count`` from ``first`` (a team of nodes can split
    a swarm); ValueError naming both when ``first`` is past the world's last robot."""
    if robots:
        return range(first, first + robots)
    if first >= world_count:
        raise ValueError('~first is %d but stageros has %d robots (robot_0 to robot_%d)'
                         % (first, world_count, world_count - 1))
    return range(first, world_count)


def first_few(indices, shown=5):
    """'robot_3, robot_7, ... (12 in all)': a list short enough for a log line."""
    names = ['robot_%d' % i for i in indices[:shown]]
    more = ', ...' if len(indices) > shown else ''
    return '%s%s (%d in all)' % (', '.join(names), more, len(indices))
