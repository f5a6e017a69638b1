"""Unit tests of multihost.harness.Probe's queries, on events fed as a probe prints them."""
import json
import time

import pytest
from multihost.harness import Probe


class _NoTeam:
    """Team.start's stand-in: the probe's lines are fed by the test, no process runs."""

    def start(self, name, i, command, on_line=None):
        return None


def _probe(events):
    probe = Probe(_NoTeam(), 'probe', 1, [])
    for event in events:
        probe._on_line(json.dumps(event))
    return probe


def _poses(robot, points, t0, step_s=0.1):
    """Pose events of robot, one per step: points are (x, v)."""
    return [{'e': 'pose', 'r': robot, 't': t0 + k * step_s, 'x': x, 'y': 0.0, 'v': v}
            for k, (x, v) in enumerate(points)]


def test_lines_that_are_not_events_are_ignored():
    probe = _probe([])
    for line in ['[INFO] [1.0]: a log line', '[1, 2]', '']:
        probe._on_line(line)
    probe._on_line(json.dumps({'e': 'ready'}))
    assert probe.ready()


@pytest.mark.parametrize(('points', 'stopped', 'stalled'), [
    ([(0.0, 0.2), (0.02, 0.2), (0.04, 0.0), (0.04, 0.0)], True, False),   # told to stop
    ([(0.0, 0.2), (0.02, 0.2), (0.02, 0.2), (0.02, 0.2)], False, True),   # against a wall
])
def test_stopped_or_stalled_at_rest(points, stopped, stalled):
    # the last pose changed 1.3 s ago, the latest came 0.1 s ago
    probe = _probe(_poses('robot_0', points + [points[-1]] * 12, time.time() - 1.6))
    assert probe.still('robot_0', 1.0)
    assert probe.stopped('robot_0', 1.0) is stopped
    assert probe.stalled('robot_0', 1.0) is stalled


def test_poses_that_stopped_coming_are_not_still():
    """Unchanged, but the last one is 2 s old: the probe (or its reader) may be behind."""
    probe = _probe(_poses('robot_0', [(0.04, 0.0)] * 5, time.time() - 2.4))
    assert not probe.moving('robot_0', 1.0)
    assert not probe.still('robot_0', 1.0)
    assert not probe.stopped('robot_0', 1.0)


def test_a_moving_robot_is_neither_stopped_nor_stalled():
    probe = _probe(_poses('robot_0', [(0.0, 0.2), (0.02, 0.2), (0.04, 0.2)], time.time() - 0.2))
    assert probe.moving('robot_0', 1.0)
    assert not probe.stopped('robot_0', 1.0)
    assert not probe.stalled('robot_0', 1.0)


def test_stalled_poses_are_the_steps_without_motion_under_a_speed():
    points = [(0.0, 0.0), (0.0, 0.0), (0.02, 0.2), (0.04, 0.2), (0.04, 0.2), (0.04, 0.0)]
    events = _poses('robot_0', points, 100.0) + _poses('robot_1', [(0.0, 0.2)], 100.0)
    probe = _probe(events)
    assert [e['t'] for e in probe.stalled_poses('robot_0')] == [pytest.approx(100.4)]
    assert probe.stalled_poses('robot_1') == []
    assert probe.stalled_poses('robot_2') == []
