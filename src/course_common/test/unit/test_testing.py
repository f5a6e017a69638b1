"""Unit tests of course_common.testing's pure helpers: results_dir, number checks, INFO lines,
ScratchDirTestCase, check_refused, free_port, Xvfb's display number (and one real Xvfb, when
installed), stamps, LogRecorder's copies of a latched line."""
import os
import re
import shutil
import socket
import unittest

import pytest
from course_common.ports import free_port
from course_common.processes import rospy_texts
from course_common.testing import (
    ScratchDirTestCase,
    check_refused,
    consecutive,
    info_texts,
    numbers_in,
    recorders,
    results_dir,
)
from course_common.testing.recorders import LogRecorder, stamp_ns
from course_common.xvfb import Xvfb, display_number
from genpy import Time
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log

from course_common import ports, testing

COUNT = re.compile(r'^hello world (\d+)$')
TIME = re.compile(r'^hello world (\d+\.\d+)$')


def test_results_dir_is_beside_rostests_xml(tmp_path):
    xml = tmp_path / 'deep' / 'TEST-x.xml'
    argv = ['test_node', '--gtest_output=xml:%s' % xml, '__name:=x']
    assert results_dir(argv) == str(tmp_path / 'deep')
    assert (tmp_path / 'deep').is_dir()  # made for the caller


def test_results_dir_outside_rostest(tmp_path, monkeypatch):
    monkeypatch.setenv('ROS_TEST_RESULTS_DIR', str(tmp_path / 'results'))
    assert results_dir(['pytest']) == str(tmp_path / 'results')
    monkeypatch.delenv('ROS_TEST_RESULTS_DIR')
    assert os.path.isdir(results_dir(['pytest']))  # the temp dir


@pytest.mark.parametrize('texts, pattern, kind, numbers', [
    ([], COUNT, int, []),
    (['hello world 0', 'hello world 12'], COUNT, int, [0, 12]),
    (['hello world 1.5', 'hello world 1700000000.25'], TIME, float, [1.5, 1700000000.25]),
])
def test_numbers_in(texts, pattern, kind, numbers):
    assert numbers_in(texts, pattern, kind) == pytest.approx(numbers, abs=1e-9)


@pytest.mark.parametrize('texts', [['hello world 1', 'hello there'], ['hello world x']])
def test_numbers_in_names_the_text_that_does_not_match(texts):
    with pytest.raises(AssertionError, match=r"unexpected text 'hello (there|world x)'"):
        numbers_in(texts, COUNT)


@pytest.mark.parametrize('values, expected', [
    ([], False),
    ([7], True),
    ([3, 4, 5], True),
    ([0, 2], False),
    ([2, 1], False),
    ([1, 1], False),
])
def test_consecutive(values, expected):
    assert consecutive(values) is expected


def test_rospy_texts_of_other_levels():
    lines = ['[INFO] [1.0]: a', '[WARN] [2.0, 0.1]: b', '[ERROR] [3.0]: c', 'd: [INFO] [4.0]: e']
    assert rospy_texts(lines, ('WARN', 'ERROR')) == ['b', 'c']
    assert rospy_texts(lines) == ['a']


def test_info_texts_keeps_rospys_info_lines_only():
    lines = ['[INFO] [1700000000.123456]: hello world 0',
             '[WARN] [1700000000.2]: careful',
             'plain output',
             '[INFO] [1700000000.3]: ',
             '[INFO] [1700000000.4]: /listener_1_2I heard hello',
             '[INFO] [1700000000.5, 12.300000]: Robot 1: waiting for team']  # on sim time
    assert info_texts(lines) == ['hello world 0', '', '/listener_1_2I heard hello',
                                 'Robot 1: waiting for team']


class _Scratch(ScratchDirTestCase):
    TMP_PREFIX = 'scratch_unit_'

    def test_path_is_in_the_folder(self):
        self.assertEqual(os.path.dirname(self.path('a.txt')), self.tmp)


def test_scratch_dir_made_and_removed():
    result = unittest.TestResult()
    suite = unittest.defaultTestLoader.loadTestsFromTestCase(_Scratch)
    suite.run(result)
    assert result.wasSuccessful(), result.failures + result.errors
    assert os.path.basename(_Scratch.tmp).startswith('scratch_unit_')
    assert not os.path.exists(_Scratch.tmp)


def _refusal(script):
    """A command line that prints 'refused' and ends with `script`'s exit."""
    return (['sh', '-c', 'echo refused; ' + script], 'refused')


@pytest.mark.parametrize('script, failed', [
    ('exit 1', False),                                    # a refusal: exit 1, the message
    ('exit 0', True),                                     # accepted: no refusal
    ('exit 2', True),                                     # another status than the nodes' 1
    ('echo Traceback; exit 1', True),                     # a crash that happens to exit 1
])
def test_check_refused_fails_the_subtest_of_each_bad_case(script, failed):
    cases = [_refusal('exit 1'), _refusal(script), (['sh', '-c', 'exit 1'], 'refused')]

    class _Refusals(unittest.TestCase):
        def test_refusals(self):
            check_refused(self, cases, timeout_s=10.0)

    result = unittest.TestResult()
    unittest.defaultTestLoader.loadTestsFromTestCase(_Refusals).run(result)
    # The third case never prints its message: its subTest fails, and only it (and the
    # second, when bad), each named by its argv.
    failed_argvs = [str(test.params['argv']) for test, _ in result.failures]
    expected = [str(c[0]) for c in (cases[1:] if failed else cases[2:])]
    assert failed_argvs == expected, result.failures


def test_free_port_can_be_bound_and_is_below_the_ephemeral_range():
    low = ports._ephemeral_low()
    for _ in range(20):
        port = free_port()
        assert ports.LOWEST_PORT <= port < low and port != ports.MASTER_PORT
        with socket.socket() as sock:
            sock.bind(('', port))  # free right now, on every address: nothing else took it


def test_free_port_passes_over_a_taken_port_and_the_default_masters(monkeypatch):
    with socket.socket() as taken:
        taken.bind(('', 0))
        taken.listen()
        free = free_port()              # a real pick: bindable now
        proposals = iter([taken.getsockname()[1], ports.MASTER_PORT, free])
        monkeypatch.setattr(ports.random, 'randrange', lambda lo, hi: next(proposals))
        assert free_port() == free


def test_ephemeral_low_reads_the_kernels_range_or_falls_back(tmp_path):
    good, bad = tmp_path / 'range', tmp_path / 'bad'
    good.write_text('40000\t60999\n')
    bad.write_text('')
    assert ports._ephemeral_low(str(good)) == 40000
    assert ports._ephemeral_low(str(bad)) == 32768
    assert ports._ephemeral_low(str(tmp_path / 'missing')) == 32768


@pytest.mark.parametrize('lines, number', [
    ([], None),
    (['_XSERVTransmkdir: Owner of /tmp/.X11-unix should be set to root'], None),
    (['warning', '42'], '42'),
    (['  7 '], '7'),
    (['0', '1'], '0'),
])
def test_display_number(lines, number):
    assert display_number(lines) == number


@pytest.mark.skipif(shutil.which('Xvfb') is None, reason='Xvfb is not installed')
def test_xvfb_starts_on_a_free_display_and_stops():
    with Xvfb((320, 240)) as first, Xvfb((320, 240)) as second:
        assert re.fullmatch(r':\d+', first.display)
        assert first.display != second.display  # -displayfd: never one in use
        assert first.env()['DISPLAY'] == first.display
        assert first.alive()
    assert not first.alive() and not second.alive()


def test_stamp_ns_of_a_header_and_of_a_clock_is_exact():
    odom = Odometry()
    odom.header.stamp = Time(12, 300000000)  # Stage's step 123: a whole 100 ms
    assert stamp_ns(odom) == 12_300_000_000
    assert stamp_ns(Clock(clock=Time(0, 100000000))) == 100_000_000


def _line(node, seq, secs, text):
    line = Log(name=node, msg=text)
    line.header.seq, line.header.stamp = seq, Time(secs, 0)
    return line


def test_log_recorder_keeps_a_line_once(monkeypatch):
    # No master: the recorder is fed as its subscriber would feed it.
    monkeypatch.setattr(recorders.rospy, 'Subscriber', lambda *args, **kwargs: None)
    log = LogRecorder(connect=False)
    for line in (_line('/talker', 1, 5, 'hello world 0'),
                 _line('/talker', 1, 5, 'hello world 0'),  # the latched line, a 2nd connection
                 _line('/talker', 2, 5, 'hello world 0'),  # said again: a new line
                 _line('/other', 1, 5, 'hello world 0'),
                 _line('/talker', 1, 9, 'hello world 0')):  # restarted under the same name
        log._cb(line)
    assert log.lines(node='/talker') == ['hello world 0'] * 3
    assert log.lines(node='/other') == ['hello world 0']
    log.clear()
    log._cb(_line('/talker', 2, 5, 'hello world 0'))
    assert log.lines() == []


@pytest.mark.parametrize('argv', [['python3', '-c', 'pass'], ['rosrun', '--debug', 'rosout'],
                                  ['rosrun', 'rosout']])
def test_rosrun_once_leaves_other_command_lines_alone(argv):
    assert testing.rosrun_once(argv) == argv


def test_rosrun_once_runs_the_file_rosrun_finds_and_looks_it_up_once():
    before = testing._rosrun_executable.cache_info()
    first = testing.rosrun_once(['rosrun', 'rosout', 'rosout', '__name:=a'])
    again = testing.rosrun_once(['rosrun', 'rosout', 'rosout'])
    after = testing._rosrun_executable.cache_info()
    assert os.path.basename(first[0]) == 'rosout' and os.access(first[0], os.X_OK)
    assert first == [first[0], '__name:=a'] and again == [first[0]]
    assert after.hits - before.hits >= 1  # the second start did not run rosrun


def test_rosrun_once_names_an_executable_rosrun_cannot_find():
    with pytest.raises(RuntimeError, match='rosrun rosout no_such_exe: not found'):
        testing.rosrun_once(['rosrun', 'rosout', 'no_such_exe'])
