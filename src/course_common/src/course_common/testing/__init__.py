"""The tests' and benchmarks' one set of helpers.

Here: the deadlines, wait_for (from course_common.waiting), pin, results_dir,
check_refused (bad command lines, side by side), rosrun_once (a rosrun command line that a
test runs many times, looked up once), and the process helpers tests use
(ChildProcess, spawn, Xvfb, free_port, cpu_ticks, rss_mb, from course_common.processes, .xvfb
and .ports, where tools use them too). Beside it: recorders (topics and /rosout), master
(queries of the graph, a private roscore, a lost subscriber), master_calls (a master that
counts its calls), views (tf checks), x_windows (the windows on an X display, and their close
button); each simulator's own helpers live with it (turtle_lite.testing, stage_lite.testing).
Production code imports course_common.waiting, .processes, .ports and .xvfb, never this.
"""
import functools
import importlib.metadata
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from concurrent.futures import ThreadPoolExecutor

from course_common.ports import free_port
from course_common.processes import (
    ChildProcess,
    cpu_ticks,
    rospy_texts,
    rss_mb,
    run_to_exit,
    spawn,
)
from course_common.waiting import POLL_S, WaitError, wait_for
from course_common.xvfb import Xvfb

__all__ = ['EVENT_DEADLINE_S', 'POLL_S', 'START_DEADLINE_S', 'ChildProcess',
           'ScratchDirTestCase', 'WaitError', 'Xvfb', 'check_refused', 'cpu_ticks', 'free_port',
           'pin',
           'consecutive', 'info_texts', 'numbers_in', 'results_dir', 'rosrun_once',
           'rospy_version', 'rss_mb', 'spawn', 'wait_for']

# Deadlines are generous: the tests run on a loaded 2-core machine, and a deadline only costs
# time when something is wrong.
START_DEADLINE_S = 30.0  # a node or tool process coming up (rosrun + Python start-up)
EVENT_DEADLINE_S = 15.0  # something that should follow promptly (a message, a log line, an exit)
GTEST_OUTPUT = '--gtest_output=xml:'
# Command lines checked side by side: each run is mostly Python start-up, so a few at a time
# save most of the wait and leave a core to the rest of the machine.
REFUSAL_WORKERS = 3


def results_dir(argv=None):
    """Where a test keeps what it made for a person to look at (screenshots, pictures):
    beside its results. rostest hands each test node --gtest_output=xml:<results file>;
    elsewhere ROS_TEST_RESULTS_DIR, else the temp dir. The folder exists on return."""
    for arg in sys.argv if argv is None else argv:
        if arg.startswith(GTEST_OUTPUT):
            path = os.path.dirname(arg[len(GTEST_OUTPUT):])
            break
    else:
        path = os.environ.get('ROS_TEST_RESULTS_DIR') or tempfile.gettempdir()
    os.makedirs(path, exist_ok=True)
    return path


def info_texts(lines):
    """The texts of rospy's INFO lines among a process's screen lines, in order, on either
    clock (course_common.processes.rospy_texts)."""
    return rospy_texts(lines)


def numbers_in(texts, pattern, kind=int):
    """The numbers (group 1 of pattern, as kind) in texts, which must all match pattern.

    Raises AssertionError naming the first text that does not (a test's failure).
    """
    found = []
    for text in texts:
        match = pattern.match(text)
        if not match:
            raise AssertionError('unexpected text %r (expected %s)' % (text, pattern.pattern))
        found.append(kind(match.group(1)))
    return found


def consecutive(values):
    """True for a non-empty run of consecutive integers (n, n+1, n+2, ...)."""
    return bool(values) and list(values) == list(range(values[0], values[0] + len(values)))


@functools.cache
def _rosrun_executable(package, executable, package_path):
    """The file `rosrun package executable` runs, as rosrun itself finds it (its --prefix
    prints the command line instead of running it); package_path keys the cache."""
    done = subprocess.run(['rosrun', '--prefix', 'printf %s\\n', package, executable],
                          capture_output=True, text=True, timeout=START_DEADLINE_S, check=False)
    found = done.stdout.splitlines()
    if done.returncode != 0 or not found or not os.access(found[0], os.X_OK):
        raise RuntimeError('rosrun %s %s: not found (%s)' % (package, executable,
                                                           (done.stdout + done.stderr).strip()))
    return found[0]


def rosrun_once(argv):
    """argv as given, or for ``['rosrun', PACKAGE, EXECUTABLE, ARGS...]`` the file rosrun runs
    followed by ARGS: rosrun looks the executable up once per test process, not at every
    start. The process is the same (rosrun execs that file, with the same environment);
    rosrun's lookup costs about 0.7 s of CPU a call (Debian's runs catkin_find twice), which
    tests that start one executable tens of times paid each time."""
    argv = list(argv)
    if len(argv) < 3 or argv[0] != 'rosrun' or argv[1].startswith('-'):
        return argv
    return [_rosrun_executable(argv[1], argv[2], os.environ.get('ROS_PACKAGE_PATH', ''))] \
        + argv[3:]


def check_refused(test, cases, timeout_s=START_DEADLINE_S, workers=REFUSAL_WORKERS):
    """Runs the argv of each (argv, expected text) of cases to its end, workers at a time, and
    checks each in a subTest of the unittest.TestCase test: exit status 1, the expected text
    in its output, no Traceback (a refusal a user can act on, not a crash). A rosrun command
    line is looked up once per executable (rosrun_once)."""
    with ThreadPoolExecutor(max_workers=workers) as pool:
        results = list(pool.map(lambda case: run_to_exit(rosrun_once(case[0]), timeout_s),
                                cases))
    for (argv, expected), (code, output) in zip(cases, results, strict=True):
        with test.subTest(argv=argv):
            test.assertEqual(code, 1, output)
            test.assertIn(expected, output)
            test.assertNotIn('Traceback', output)


class ScratchDirTestCase(unittest.TestCase):
    """A TestCase with a scratch folder for the whole class (path(name) in it), removed after.

    TMP_PREFIX names the folder, so a folder left by a killed run says whose it was.
    """

    TMP_PREFIX = 'course_test_'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.tmp = tempfile.mkdtemp(prefix=cls.TMP_PREFIX)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)
        super().tearDownClass()

    def path(self, name):
        return os.path.join(self.tmp, name)


def rospy_version():
    """The installed rospy's version, for messages ('unknown' if its metadata is missing)."""
    try:
        return importlib.metadata.version('rospy')
    except importlib.metadata.PackageNotFoundError:
        return 'unknown'


def pin(ok, attribute, meaning):
    """Fail, naming the rospy attribute, what it should mean and rospy's version, unless ok.

    For the tests that pin the rospy internals course_common.rospy_internals relies on.
    """
    if not ok:
        raise AssertionError('installed rospy %s: %s no longer %s (course_common.rospy_internals '
                             'relies on it)' % (rospy_version(), attribute, meaning))
