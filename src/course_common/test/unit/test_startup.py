"""course_common.startup: every workspace node asks the master once for rospy's /rosout param.

rospy asks the master for /rosout_disable_topics_generation on every log line while that
parameter is unset (a plain roscore). The first test runs a logging node against a master
in this process that records every call (no roscore) and fails if the node asks again per
line; the second pins that plain rospy still does (if it stops, startup's seeding can go);
one checks that init_node makes rospy connect every subscription (rospy_internals tests how);
the last fails if a node of the workspace starts without course_common.startup.init_node.
"""
import os
import re
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from course_common.testing.master_calls import CountingMaster

LINES = 30
RUN_TIMEOUT_S = 60.0  # a fresh interpreter importing rospy, 30 lines at 50 Hz; loaded machine
# A node that logs LINES lines at 50 Hz, started with startup.init_node or rospy.init_node.
PROBE = '''
import sys
import rospy
from course_common.startup import init_node
(init_node if sys.argv[1] == 'startup' else rospy.init_node)('rosout_probe')
rate = rospy.Rate(50)
for i in range(%d):
    rospy.loginfo('line %%d', i)
    rate.sleep()
''' % LINES
SRC = Path(__file__).resolve().parents[3]
# The lab's own scripts, kept as students type them (beginner_tutorials' README says so).
EXEMPT = {'basics/beginner_tutorials/scripts/talker.py',
          'basics/beginner_tutorials/scripts/listener.py'}


@pytest.fixture
def master():
    m = CountingMaster()
    yield m
    m.stop()


def probe_env(master):
    env = dict(os.environ, ROS_MASTER_URI=master.uri)
    # Everything runs on this machine: name it localhost unless the user chose a name, so a
    # hostname that does not resolve (a bare container) cannot keep the probe from its master.
    if not env.get('ROS_HOSTNAME') and not env.get('ROS_IP'):
        env['ROS_HOSTNAME'] = 'localhost'
    return env


def run_probe(master, start):
    done = subprocess.run([sys.executable, '-c', PROBE, start], capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S, env=probe_env(master), check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.count('line ') == LINES, done.stdout
    return master.calls(caller='/rosout_probe', method='subscribeParam')


def test_startup_asks_the_master_once_not_per_log_line(master):
    calls = run_probe(master, 'startup')
    assert len(calls) == 1, ('%d subscribeParam calls for %d log lines: a node started with '
                             'course_common.startup asks the master per line' % (len(calls), LINES))


def test_plain_rospy_still_asks_per_log_line(master):
    calls = run_probe(master, 'rospy')
    assert len(calls) >= LINES, ('rospy asked the master %d times for %d log lines: it caches '
                                 '/rosout_disable_topics_generation now, so '
                                 'startup.cache_rosout_param may go' % (len(calls), LINES))


CONNECTS_ALL = '''
import rospy.impl.registration as registration
import rospy.impl.tcpros_base as tcpros_base
from course_common.startup import init_node
init_node('connect_probe')
print(getattr(tcpros_base.TCPServer._create_server_sock, 'deep_backlog', False),
      getattr(registration.RegManager.publisher_update, 'keeps_every_update', False))
'''


def test_startup_connects_every_subscriber_and_publisher(master):
    # rospy_internals.deep_tcpros_backlog and keep_every_publisher_update, tested there,
    # installed by init_node
    done = subprocess.run([sys.executable, '-c', CONNECTS_ALL], capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S, env=probe_env(master), check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == 'True True', done.stdout


def _node_sources():
    for path in sorted(SRC.rglob('*')):
        rel = path.relative_to(SRC).as_posix()
        if not path.is_file() or '/test/' in '/' + rel or rel in EXEMPT:
            continue
        if path.suffix == '.py' or path.parent.name == 'scripts':
            yield rel, path.read_text(errors='replace')


def test_every_node_starts_with_course_common_startup():
    plain = [rel for rel, text in _node_sources()
             if re.search(r'\brospy\.init_node\(', text) and rel != 'course_common/src/'
             'course_common/startup.py']
    assert plain == [], ('these call rospy.init_node: use course_common.startup.init_node, '
                         'which asks the master once for /rosout_disable_topics_generation')


# A loop that publishes, with ROS shutting down between its is_shutdown() check and its
# publish, as when a node of the same name takes over: rospy's own pre-shutdown hook closes
# every topic, then this probe's hook (added after it) holds the shutdown until the loop has
# published to the closed topic. How the loop runs is argv[1]: loop_at_rate, or a rospy.Timer.
RACE_DEADLINE_S = 20.0
RACE_PROBE = '''
import sys
import threading
import rospy
from std_msgs.msg import String
from course_common.rospy_internals import add_preshutdown_hook
from course_common.startup import init_node, loop_at_rate, quiet_at_shutdown
init_node('closed_topic_probe')
pub = rospy.Publisher('chatter', String, queue_size=1)
topics_closed, published, ended = threading.Event(), threading.Event(), threading.Event()
def hold_shutdown(_reason):
    topics_closed.set()
    published.wait(%(deadline)s)
add_preshutdown_hook(hold_shutdown)
def cycle(*_event):
    if ended.is_set():
        return
    if not topics_closed.is_set():
        threading.Thread(target=rospy.signal_shutdown, args=('same name',)).start()
        topics_closed.wait(%(deadline)s)
    try:
        pub.publish('hello')
    finally:
        published.set()
    print('published to a closed topic', flush=True)
if sys.argv[1] == 'loop_at_rate':
    loop_at_rate(50, cycle)
else:
    def tick(event):
        try:
            quiet_at_shutdown(cycle)(event)
        finally:
            ended.set()
    rospy.Timer(rospy.Duration(0.02), tick, oneshot=True)
    ended.wait(%(deadline)s)
print('ended' if published.is_set() else 'never published', flush=True)
''' % {'deadline': RACE_DEADLINE_S}


@pytest.mark.parametrize('loop', ['loop_at_rate', 'timer'])
def test_a_loop_ends_quietly_when_shutdown_closes_its_topic(master, loop):
    done = subprocess.run([sys.executable, '-c', RACE_PROBE, loop], capture_output=True,
                          text=True, timeout=RUN_TIMEOUT_S, env=probe_env(master), check=False)
    assert done.returncode == 0, done.stderr
    # The publish did fail (the race happened), and nothing but rospy's own lines reached
    # stderr: no traceback, no "closed topic".
    assert done.stdout.split('\n')[-2:] == ['ended', ''], done.stdout + done.stderr
    assert 'published to a closed topic' not in done.stdout, done.stdout
    assert 'Traceback' not in done.stderr and 'closed topic' not in done.stderr, done.stderr


# A signal that arrives while the node holds a lock its shutdown needs (rospy's log file's
# writer, a connection's lock): a shutdown hook that takes the main thread's lock stands for
# them. argv: how the node starts (startup or rospy), then the signal's number.
HOOK_LOCK_WAIT_S = 2.0
SIGNAL_PROBE = '''
import os, sys, threading, time
import rospy
from course_common.rospy_internals import add_preshutdown_hook, shutdown_requested
from course_common.startup import init_node
(init_node if sys.argv[1] == 'startup' else rospy.init_node)('signal_probe')
held, hook_ran = threading.Lock(), threading.Event()
def needs_the_lock(_reason):
    got = held.acquire(timeout=%(wait)s)
    where = 'main' if threading.current_thread() is threading.main_thread() else 'thread'
    print('hook in', where, 'got the lock' if got else 'without the lock', flush=True)
    hook_ran.set()
add_preshutdown_hook(needs_the_lock)
with held:
    os.kill(os.getpid(), int(sys.argv[2]))
    deadline = time.monotonic() + %(wait)s * 2
    while not shutdown_requested() and time.monotonic() < deadline:
        time.sleep(0.001)
    print('requested', shutdown_requested(), 'hook ran', hook_ran.is_set(), flush=True)
print('main done', flush=True)
''' % {'wait': HOOK_LOCK_WAIT_S}


def run_signal_probe(master, start, signum):
    done = subprocess.run([sys.executable, '-c', SIGNAL_PROBE, start, str(int(signum))],
                          capture_output=True, text=True, timeout=RUN_TIMEOUT_S,
                          env=probe_env(master), check=False)
    return done.returncode, done.stdout.splitlines(), done.stderr


@pytest.mark.parametrize('signum', [signal.SIGINT, signal.SIGTERM], ids=['SIGINT', 'SIGTERM'])
def test_a_signal_shuts_the_node_down_outside_what_it_interrupted(master, signum):
    code, lines, stderr = run_signal_probe(master, 'startup', signum)
    assert code == 0, stderr
    # Requested at once (a loop stops), the hook not yet run: the handler only marked it.
    assert lines[0] == 'requested True hook ran False', lines
    # The shutdown ran in a thread and got the lock once the main thread let it go, and the
    # exit waited for it although the main thread had finished.
    assert sorted(lines[1:]) == ['hook in thread got the lock', 'main done'], lines
    assert 'Traceback' not in stderr, stderr


def test_plain_rospy_still_shuts_down_inside_the_signal(master):
    code, lines, _ = run_signal_probe(master, 'rospy', signal.SIGINT)
    assert code == 0
    assert lines[0] == 'hook in main without the lock', (
        'rospy no longer runs its shutdown inside the signal handler (%r): '
        'rospy_internals.shut_down_off_the_signal may go' % lines)
