"""Unit tests for multi_sync.lesson_report: a robot's course, stop reasons, the summary."""
import pytest
from multi_sync.lesson_report import Track, monitor_lines, stop_reasons, summary_lines

TOL = 1e-9  # m: sums of a few exact differences


def test_track_follows_a_course():
    track = Track()
    assert not track.moved() and not track.stopped()
    track.on_pose(-11.5, 23.5, 0.0)
    track.on_pose(-11.5 + 0.04, 23.5, 0.2)
    assert not track.moved()  # 4 cm: not yet
    track.on_pose(-11.5 + 0.5, 23.5, 0.2)
    track.on_pose(-11.5 + 0.5, 23.5 + 0.3, 0.2)
    assert track.moved()
    assert track.path_m == pytest.approx(0.8, abs=TOL)
    assert track.start == (-11.5, 23.5) and track.pose == (-11.0, 23.8)


@pytest.mark.parametrize('command, speed, stopped', [
    (0.0, 0.0, True),
    (0.2, 0.0, False),    # stalled: standing, but still commanded to move
    (0.0, 0.2, False),    # commanded 0, not yet standing (the next step)
    (None, 0.0, False),   # never commanded
])
def test_stopped_means_commanded_zero_and_standing(command, speed, stopped):
    track = Track()
    track.on_pose(0.0, 0.0, 0.0)
    track.on_pose(1.0, 0.0, speed)
    if command is not None:
        track.on_command(command)
    assert track.stopped() is stopped


def test_a_robot_that_never_moved_has_not_stopped():
    track = Track()
    track.on_pose(0.0, 0.0, 0.0)
    track.on_command(0.0)
    assert not track.stopped()


def test_stop_reasons_keep_each_robots_last_line():
    texts = ['Robot 0: Team is ready. Let\'s move!',
             'Robot 1: robot 0 is 0.98 m ahead, waiting',
             'Robot 0: laser: obstacle 0.49 m ahead, stopping',
             'Robot 2: wall 0.50 m ahead, stopping',
             'Robot 1: path clear, moving on',
             'Robot 1: robot 0 is 0.97 m ahead, waiting',
             'Robot 7: wall 0.50 m ahead, stopping']  # outside the team of 4: ignored
    assert stop_reasons(texts, 4) == ['Robot 0: laser: obstacle 0.49 m ahead, stopping',
                                      'Robot 1: robot 0 is 0.97 m ahead, waiting',
                                      'Robot 2: wall 0.50 m ahead, stopping', None]


def test_monitor_lines_in_order():
    texts = ['Waiting for robots to connect...', 'Robot 0: waiting for team', 'Robot 2 is ready!',
             'Robot 12 is ready!', 'All robots GO!', 'All robots GO! (not quite)']
    assert monitor_lines(texts) == ['Waiting for robots to connect...', 'Robot 2 is ready!',
                                    'Robot 12 is ready!', 'All robots GO!']


def test_summary_rows():
    track = Track()
    track.on_pose(-11.5, 23.5, 0.0)
    track.on_pose(-10.12, 23.5, 0.0)
    lines = summary_lines([track, track], ['Robot 0: laser: obstacle 0.49 m ahead, stopping',
                                           None], ['All robots GO!'])
    assert lines[0] == 'monitor: All robots GO!'
    assert lines[-2] == ('| robot_0 | 1.38 | (-10.12, 23.50) | '
                         'Robot 0: laser: obstacle 0.49 m ahead, stopping |')
    assert lines[-1].endswith('| (no stop line logged) |')
    with pytest.raises(ValueError):
        summary_lines([track], [None, None], [])
