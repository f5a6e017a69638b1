"""Unit tests of course_common.processes: the one child-process runner, and /proc readings.

The runner is tested on /bin/sh and python3 children (no ROS): lines read as they come,
SIGINT first, SIGKILL for a child that ignores it, a terminal, a log file.
"""
import os
import signal
import subprocess
import sys
import termios
import time

import pytest
from course_common.processes import (
    ChildProcess,
    cpu_ticks,
    descendants,
    peak_rss_mb,
    pid_running,
    process_table,
    rss_mb,
    run_to_exit,
    spawn,
    split_lines,
    stat_cpu_ticks,
    stat_state,
    status_rss_mb,
)
from course_common.waiting import WaitError, wait_for

DEADLINE_S = 10.0  # a shell starting and printing a line, on a loaded machine

# A child that says it is ready, then reports SIGINT by printing and exiting 3.
ON_SIGINT = ('import signal, sys, time\n'
             'def bye(*_):\n'
             '    print("got SIGINT", flush=True)\n'
             '    sys.exit(3)\n'
             'signal.signal(signal.SIGINT, bye)\n'
             'print("ready", flush=True)\n'
             'time.sleep(60)\n')
IGNORES_SIGINT = ('import signal, time\n'
                  'signal.signal(signal.SIGINT, signal.SIG_IGN)\n'
                  'print("ready", flush=True)\n'
                  'time.sleep(60)\n')


@pytest.mark.parametrize('text, final, lines', [
    ('', False, []),
    ('', True, []),
    ('a\nb\n', False, ['a', 'b']),
    ('a\nb', False, ['a']),  # b may not be finished
    ('a\nb', True, ['a', 'b']),
    ('a\r\nb\r\n', False, ['a', 'b']),  # a terminal's line ends
    ('\n\n', False, ['', '']),
    ('x\r', True, ['x']),
])
def test_split_lines(text, final, lines):
    assert split_lines(text, final) == lines


@pytest.mark.parametrize('line, ticks', [
    ('1 (sh) S 0 1 1 0 -1 4194560 100 0 0 0 7 5 0 0 20 0 1 0 1 0 0', 12),
    ('42 (a ) b) R 1 42 42 0 -1 0 0 0 0 0 30 12 0 0 20 0 1 0 5 0 0', 42),  # ') ' in the name
])
def test_stat_cpu_ticks(line, ticks):
    assert stat_cpu_ticks(line) == ticks


def test_stat_cpu_ticks_rejects_a_short_line():
    with pytest.raises(IndexError):
        stat_cpu_ticks('1 (sh) S 0')


STATUS = 'Name:\tsh\nVmHWM:\t    3072 kB\nVmRSS:\t    2048 kB\nThreads:\t1\n'


@pytest.mark.parametrize('text, field, mb', [
    (STATUS, 'VmRSS', 2.0),
    (STATUS, 'VmHWM', 3.0),  # the peak, a line before VmRSS
    ('Name:\tzombie\nState:\tZ\n', 'VmRSS', None),
    ('Name:\tzombie\nState:\tZ\n', 'VmHWM', None),
])
def test_status_rss_mb(text, field, mb):
    assert status_rss_mb(text, field) == (None if mb is None else pytest.approx(mb, abs=1e-9))


def test_this_process_has_cpu_ticks_and_memory():
    assert cpu_ticks(os.getpid()) >= 0
    rss = rss_mb(os.getpid())
    assert rss > 1.0  # a Python interpreter is several MB
    assert peak_rss_mb(os.getpid()) >= rss  # read after: the peak so far is never below


def test_process_table_and_descendants_of_a_child_and_its_grandchild():
    # sh starts sleep in the background and says its pid: child (sh) and grandchild (sleep)
    with ChildProcess(['sh', '-c', 'sleep 30 & echo "grandchild $!"; wait']) as proc:
        grandchild = int(proc.wait_line('grandchild ', DEADLINE_S).split()[1])
        table = process_table()
        assert table[os.getpid()][0] == os.getppid()
        assert table[proc.pid] == (os.getpid(), 'sh -c sleep 30 & echo "grandchild $!"; wait')
        assert table[grandchild] == (proc.pid, 'sleep 30')
        assert sorted(descendants(proc.pid)) == sorted([proc.pid, grandchild])
        assert descendants(grandchild, table) == [grandchild]
        assert os.getpid() in descendants(os.getppid(), table)
    assert descendants(proc.pid) == []  # stopped: gone, and its grandchild with it


def test_lines_are_read_as_they_come_and_exit_code_is_returned():
    proc = spawn(['sh', '-c', 'echo one; echo two >&2; printf three'])
    assert proc.wait_exit(DEADLINE_S) == 0
    assert proc.lines() == ['one', 'two', 'three']  # stderr merged; the last line once ended
    assert proc.printed('two') and not proc.printed('four')
    assert proc.output() == 'one\ntwo\nthree'
    assert proc.stop() == 0  # stop() of an ended process: its code


def test_wait_line_returns_the_first_matching_line():
    with ChildProcess(['sh', '-c', 'echo start; echo "x: 1"; echo "x: 2"; sleep 30']) as proc:
        assert proc.wait_line('x: ', DEADLINE_S) == 'x: 1'
        assert proc.alive()


def test_wait_line_fails_at_once_when_the_process_ends_without_it():
    proc = spawn(['sh', '-c', 'echo something else'])
    started = time.monotonic()
    with pytest.raises(WaitError, match='has exited.*\n.*something else'):
        proc.wait_line('never printed', 60.0)
    assert time.monotonic() - started < 30.0  # not the whole deadline
    proc.stop()


def test_stop_sends_sigint_first():
    proc = spawn([sys.executable, '-c', ON_SIGINT])
    proc.wait_line('ready', DEADLINE_S)
    assert proc.stop() == 3
    assert proc.printed('got SIGINT')
    assert proc.stop() == 3  # idempotent


def test_stop_kills_a_process_that_ignores_sigint():
    proc = spawn([sys.executable, '-c', IGNORES_SIGINT], stop_timeout_s=0.5)
    proc.wait_line('ready', DEADLINE_S)
    assert proc.stop() is None  # it had to be killed
    assert proc.exited() and proc.returncode == -signal.SIGKILL


def test_stop_kills_what_the_process_left_in_its_session():
    proc = spawn(['sh', '-c', 'sleep 60 & echo $!; wait'])
    child = int(proc.wait_line('', DEADLINE_S))
    proc.stop()
    wait_for(lambda: not pid_running(child), DEADLINE_S,
             'the grandchild killed with the session')


def test_interrupt_then_wait_exit():
    proc = spawn([sys.executable, '-c', ON_SIGINT])
    proc.wait_line('ready', DEADLINE_S)
    proc.interrupt()
    assert proc.wait_exit(DEADLINE_S) == 3
    proc.stop()


def test_wait_exit_fails_naming_a_process_still_running():
    with ChildProcess(['sleep', '30']) as proc, pytest.raises(WaitError, match='sleep 30 still'):
        proc.wait_exit(0.2)


def test_env_adds_and_removes_variables(monkeypatch):
    monkeypatch.setenv('H2A_GONE', 'here')
    proc = spawn(['sh', '-c', 'echo "[$H2A_NEW] [${H2A_GONE-unset}] [$PYTHONUNBUFFERED]"'],
                 env={'H2A_NEW': 'new', 'H2A_GONE': None})
    assert proc.wait_exit(DEADLINE_S) == 0
    assert proc.lines() == ['[new] [unset] [1]']


def test_stdin_is_not_the_tests():
    proc = spawn(['sh', '-c', 'if [ -t 0 ]; then echo tty; else cat; echo eof; fi'])
    assert proc.wait_exit(DEADLINE_S) == 0
    assert proc.lines() == ['eof']


def test_log_file_gets_the_output(tmp_path):
    log = tmp_path / 'child.log'
    proc = spawn(['sh', '-c', 'echo logged; echo twice'], log_path=str(log))
    proc.wait_exit(DEADLINE_S)
    proc.stop()
    assert log.read_text() == 'logged\ntwice\n'
    assert proc.tail(1) == 'twice'


def test_terminal_child_sees_a_terminal_and_gets_keys():
    script = 'if [ -t 0 ]; then echo tty; fi; read line; echo "got $line"'
    proc = ChildProcess(['sh', '-c', script], terminal=True).start()
    proc.wait_line('tty', DEADLINE_S)
    assert proc.terminal_lflags() & termios.ICANON  # a cooked terminal, as opened
    proc.send(b'abc\n')
    proc.wait_line('got abc', DEADLINE_S)
    assert proc.wait_exit(DEADLINE_S) == 0
    proc.stop()


def test_hang_up_ends_a_terminal_child():
    proc = ChildProcess(['sh', '-c', 'echo ready; read line; echo "read: $?"'],
                        terminal=True).start()
    proc.wait_line('ready', DEADLINE_S)
    proc.hang_up()
    proc.wait_exit(DEADLINE_S)  # read fails on the closed terminal: the shell goes on and ends
    proc.stop()


def test_start_twice_is_an_error():
    with ChildProcess(['sleep', '30']) as proc, pytest.raises(RuntimeError, match='already'):
        proc.start()


def test_stop_before_start_returns_none():
    assert ChildProcess(['true']).stop() is None


def test_on_line_gets_each_complete_line_once():
    got = []
    proc = spawn(['sh', '-c', 'printf "a\\nb"; sleep 0.2; printf "c\\r\\nd"'], on_line=got.append)
    proc.wait_exit(DEADLINE_S)
    proc.stop()
    assert got == ['a', 'bc', 'd']  # 'b' waited for the rest of its line; 'd' at the end


def test_stop_with_a_shorter_timeout_kills_sooner():
    proc = spawn([sys.executable, '-c', IGNORES_SIGINT])
    proc.wait_line('ready', DEADLINE_S)
    started = time.monotonic()
    assert proc.stop(0.2) is None
    assert time.monotonic() - started < proc.stop_timeout_s


@pytest.mark.parametrize('script, code, output', [
    ('echo out; echo err >&2; exit 4', 4, 'out\nerr\n'),
    ('true', 0, ''),
])
def test_run_to_exit(script, code, output):
    assert run_to_exit(['sh', '-c', script], DEADLINE_S) == (code, output)


def test_run_to_exit_stops_a_process_past_its_time():
    with pytest.raises(WaitError, match='still running'):
        run_to_exit(['sleep', '30'], 0.2)


@pytest.mark.parametrize('terminal', [False, True])
def test_no_such_program_raises_and_leaves_no_fd_open(tmp_path, terminal):
    before = len(os.listdir('/proc/self/fd'))
    with pytest.raises(FileNotFoundError):
        spawn([str(tmp_path / 'missing')], terminal=terminal, log_path=str(tmp_path / 'log'))
    assert len(os.listdir('/proc/self/fd')) == before


def test_many_small_writes_keep_every_line_in_order():
    proc = spawn([sys.executable, '-c', 'for i in range(5000): print(i)'])
    assert proc.wait_exit(DEADLINE_S) == 0
    assert proc.lines() == [str(i) for i in range(5000)]
    assert proc.tail(2) == '4998\n4999'
    proc.stop()


@pytest.mark.parametrize('line, state', [
    ('42 (sleep) S 1 42 42 0 -1', 'S'),
    ('43 (a ) Z name) Z 1 43 43 0 -1', 'Z'),  # a name may hold ') '
    ('44 (python3) R 1 44 44 0 -1', 'R'),
])
def test_stat_state(line, state):
    assert stat_state(line) == state


def test_pid_running_counts_neither_a_zombie_nor_a_reaped_child():
    import subprocess
    assert pid_running(os.getpid())
    child = subprocess.Popen(['true'])
    wait_for(lambda: not pid_running(child.pid), DEADLINE_S, 'the child to end (a zombie)')
    assert os.path.exists('/proc/%d' % child.pid)  # not reaped yet: a zombie
    child.wait()
    assert not pid_running(child.pid)


# A parent that ignores Ctrl-C (as a shell's background job does), then starts ON_SIGINT's
# twin with a default SIGINT through ChildProcess and interrupts it: exit code and output.
IGNORING_PARENT = ('import signal, sys\n'
                   'signal.signal(signal.SIGINT, signal.SIG_IGN)\n'
                   'from course_common.processes import ChildProcess\n'
                   'child = ChildProcess([sys.executable, "-c", "import time\\n'
                   'print(\'ready\', flush=True)\\ntime.sleep(60)"]).start()\n'
                   'child.wait_line("ready", 20)\n'
                   'child.interrupt()\n'
                   'print(child.wait_exit(20))\n')


def test_ctrl_c_reaches_a_child_of_a_parent_that_ignores_it():
    done = subprocess.run([sys.executable, '-c', IGNORING_PARENT], capture_output=True,
                          text=True, timeout=60, check=False)
    assert done.stdout.split() == [str(-signal.SIGINT)], done.stderr
