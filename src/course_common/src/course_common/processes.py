"""ChildProcess: the workspace's one runner of child processes (spawn, read lines, SIGINT, kill).

Used by the tools (convoy_demo's roslaunch and rosbag record, rviz_snapshot's rviz and Xvfb),
the rostest nodes and the benchmarks. Also what a benchmark reads of a process in /proc:
cpu_ticks, rss_mb, peak_rss_mb, whether it still runs (pid_running) and the process tree
(process_table, descendants); and the texts of the rospy log lines a process printed
(rospy_texts).
"""
import codecs
import contextlib
import os
import re
import select
import signal
import subprocess
import termios
import threading

from course_common.waiting import WaitError, wait_for

STOP_TIMEOUT_S = 15.0  # Ctrl-C to exit: rospy and roslaunch need a few seconds under load
EXIT_TIMEOUT_S = 15.0  # wait_exit's default: a process that should end promptly
# How soon the reader of a terminal notices that the process has ended (a terminal, which
# this process also holds open, never reports an end; a pipe does, so its reader just blocks).
TERMINAL_POLL_S = 0.1
TAIL_LINES = 15  # lines of output quoted when a wait fails
#: /proc/<pid>/stat fields after the command name ("pid (comm) state ppid ..."): utime and
#: stime are fields 14 and 15 of the whole line, 12 and 13 after the name (0-based 11, 12).
STAT_UTIME, STAT_STIME = 11, 12
#: rospy's log line on a terminal: "[INFO] [<wall time>]: <text>" on wall time, "[INFO]
#: [<wall time>, <sim time>]: <text>" on sim time. Groups: level, sim time (None), text.
ROSPY_LINE = re.compile(r'^\[(DEBUG|INFO|WARN|ERROR|FATAL)\] \[[\d.]+(?:, ([\d.]+))?\]: (.*)$')


def rospy_texts(lines, levels=('INFO',)):
    """The texts of rospy's log lines of the given levels among a process's output lines, in
    order, on either clock (a node on Stage's sim time prints both times)."""
    return [m.group(3) for m in map(ROSPY_LINE.match, lines) if m and m.group(1) in levels]


def split_lines(text, final=False):
    """The lines of text without their ends ('\\n' or a terminal's '\\r\\n').

    The last, unfinished line is left out (more of it may come) unless final is true.
    """
    parts = text.split('\n')
    rest = parts.pop()
    if final and rest:
        parts.append(rest)
    return [part[:-1] if part.endswith('\r') else part for part in parts]


def stat_cpu_ticks(stat_line):
    """utime + stime, in clock ticks, of a /proc/<pid>/stat line (the name may hold ') ')."""
    fields = stat_line.rsplit(')', 1)[1].split()
    return int(fields[STAT_UTIME]) + int(fields[STAT_STIME])


def process_table():
    """pid -> (parent pid, command line) of every process running now (from /proc)."""
    table = {}
    for pid in filter(str.isdigit, os.listdir('/proc')):
        try:
            with open('/proc/%s/stat' % pid) as f:
                ppid = int(f.read().rsplit(')', 1)[1].split()[1])
            with open('/proc/%s/cmdline' % pid, 'rb') as f:
                cmdline = f.read().replace(b'\0', b' ').decode(errors='replace').strip()
        except (OSError, IndexError, ValueError):
            continue  # the process ended while we looked
        table[int(pid)] = (ppid, cmdline)
    return table


def descendants(root, table=None):
    """root and every process under it that runs now (a process_table() may be given)."""
    table = process_table() if table is None else table
    children = {}
    for pid, (ppid, _) in table.items():
        children.setdefault(ppid, []).append(pid)
    pids, todo = [], [root]
    while todo:
        pid = todo.pop()
        if pid in table:
            pids.append(pid)
        todo.extend(children.get(pid, ()))
    return pids


def stat_state(stat_line):
    """The state letter (R, S, Z, ...) of a /proc/<pid>/stat line (the name may hold ') ')."""
    return stat_line.rsplit(')', 1)[1].split()[0]


def pid_running(pid):
    """True while process pid runs: a pid that is gone, or a zombie (ended, only its
    parent's wait missing), does not."""
    try:
        with open('/proc/%d/stat' % pid, encoding='ascii', errors='replace') as stat:
            return stat_state(stat.read()) != 'Z'
    except (OSError, IndexError):
        return False


def cpu_ticks(pid):
    """CPU time (user + system) the process has used so far, in clock ticks (SC_CLK_TCK)."""
    with open('/proc/%d/stat' % pid) as stat:
        return stat_cpu_ticks(stat.read())


def status_rss_mb(status_text, field='VmRSS'):
    """VmRSS (or another kB field, such as the peak VmHWM) of a /proc/<pid>/status text in MB
    (MiB), or None when it has none (a zombie)."""
    for line in status_text.splitlines():
        if line.startswith(field + ':'):
            return int(line.split()[1]) / 1024.0
    return None


def rss_mb(pid):
    """The process's resident set size in MB (MiB), or None when it has none."""
    with open('/proc/%d/status' % pid) as status:
        return status_rss_mb(status.read())


def peak_rss_mb(pid):
    """The process's peak resident set size so far (VmHWM) in MB (MiB), or None."""
    with open('/proc/%d/status' % pid) as status:
        return status_rss_mb(status.read(), 'VmHWM')


#: The signals a terminal's keys send (Ctrl-C, Ctrl-\\), at their defaults in a job it starts.
TERMINAL_SIGNALS = (signal.SIGINT, signal.SIGQUIT)


def _terminal_signals_if_ignored():
    """What a child runs before exec so that TERMINAL_SIGNALS act on it (None when this
    process does not ignore them: a child's handled signals are reset by exec anyway)."""
    if not any(signal.getsignal(s) == signal.SIG_IGN for s in TERMINAL_SIGNALS):
        return None
    return _default_terminal_signals


def _default_terminal_signals():
    for s in TERMINAL_SIGNALS:
        signal.signal(s, signal.SIG_DFL)


class ChildProcess:
    """A child process in a session of its own, its output read as it comes; a context manager.

    stdout and stderr are merged and read by a thread, so output() and lines() show what the
    process printed so far (Python children run unbuffered); log_path also writes it to a file
    a person can read after the run. terminal=True runs the process on a pseudo-terminal
    (stdin, stdout and stderr), as in a terminal window: send() types, terminal_lflags() reads
    its mode, hang_up() closes the window. stdin is /dev/null otherwise.

    stop() sends SIGINT to the session, as Ctrl-C in a terminal does to what runs in it (ROS
    tools then shut down cleanly: roslaunch stops its nodes and master, rosbag record closes
    its bag, a node sends its last command), and SIGKILLs the session if the process has not
    exited after stop_timeout_s. Its Ctrl-C and Ctrl-\\ act as in a terminal's job even when
    this process ignores them (a shell's background job, `cmd &`, does, and children inherit
    what is ignored).
    env: variables added to this process's environment (a value None removes one).
    on_line: called by the reader with each complete output line, as it comes.
    """

    stop_timeout_s = STOP_TIMEOUT_S

    def __init__(self, argv=None, env=None, log_path=None, terminal=False, cwd=None,
                 stop_timeout_s=None, on_line=None):
        self.argv = None if argv is None else list(argv)
        self.env = dict(env or {})
        self.log_path = log_path
        self.terminal = terminal
        self.cwd = cwd
        if stop_timeout_s is not None:
            self.stop_timeout_s = stop_timeout_s
        self.on_line = on_line
        self.proc = None
        self._lock = threading.Lock()
        self._chunks = []  # the output as read; output() joins them
        self._lines = []  # its complete lines
        self._partial = ''  # the unfinished last line
        self._finished = threading.Event()
        self._reader = None
        self._fd = None  # what the reader reads: the pipe, or the terminal's master side
        self._slave = None
        self._log = None
        self._stopped = False
        self._code = None

    # --- start -------------------------------------------------------------------------
    def start(self, argv=None):
        """Starts argv (or the constructor's); returns self."""
        if self.proc is not None:
            raise RuntimeError('%s already started' % self.name)
        if argv is not None:
            self.argv = list(argv)
        env = dict(os.environ, PYTHONUNBUFFERED='1')
        env.update(self.env)
        env = {k: v for k, v in env.items() if v is not None}
        if self.log_path:
            self._log = open(self.log_path, 'w', encoding='utf-8')  # noqa: SIM115 (reader closes)
        if self.terminal:
            self._fd, self._slave = os.openpty()
            streams = {'stdin': self._slave, 'stdout': self._slave, 'stderr': self._slave}
        else:
            streams = {'stdin': subprocess.DEVNULL, 'stdout': subprocess.PIPE,
                       'stderr': subprocess.STDOUT}
        try:
            self.proc = subprocess.Popen(self.argv, env=env, cwd=self.cwd,
                                         start_new_session=True,
                                         preexec_fn=_terminal_signals_if_ignored(), **streams)
        except OSError:  # no such program: leave nothing open behind
            for fd in (self._fd, self._slave):
                if fd is not None:
                    os.close(fd)
            if self._log is not None:
                self._log.close()
            raise
        if not self.terminal:
            self._fd = self.proc.stdout.fileno()
        self._reader = threading.Thread(target=self._read, daemon=True,
                                        name='output of %s' % self.name)
        self._reader.start()
        return self

    @property
    def name(self):
        return ' '.join(self.argv or ['(no command)'])

    @property
    def pid(self):
        return self.proc.pid

    @property
    def returncode(self):
        return None if self.proc is None else self.proc.poll()

    def _read(self):
        decoder = codecs.getincrementaldecoder('utf-8')(errors='replace')
        fd = self._fd
        poll_s = TERMINAL_POLL_S if self.terminal else None
        while True:
            try:
                ready, _, _ = select.select([fd], [], [], poll_s)
                data = os.read(fd, 65536) if ready else None
            except (OSError, ValueError):  # a terminal's other side closed (EIO), or hang_up()
                break
            if data == b'':  # the pipe's end: the process and all it started are gone
                break
            if data:
                self._append(decoder.decode(data))
            elif self.proc.poll() is not None:  # a terminal never ends: the process did
                break
        self._append(decoder.decode(b'', final=True))
        if self.on_line is not None and self._partial:
            self.on_line(self._partial.removesuffix('\r'))
        if self._log is not None:
            self._log.close()
        self._finished.set()

    def _append(self, text):
        if not text:
            return
        lines = split_lines(self._partial + text)
        with self._lock:
            self._chunks.append(text)
            self._lines.extend(lines)
            self._partial = (self._partial + text).rpartition('\n')[2]
        if self._log is not None:
            self._log.write(text)
            self._log.flush()
        if self.on_line is not None:
            for line in lines:
                self.on_line(line)

    # --- what it printed ---------------------------------------------------------------
    def output(self):
        """Everything it printed so far, as one text."""
        with self._lock:
            if len(self._chunks) > 1:
                self._chunks[:] = [''.join(self._chunks)]
            return self._chunks[0] if self._chunks else ''

    def lines(self):
        """Its complete output lines so far (the last one too once it has ended)."""
        finished = self._finished.is_set()
        with self._lock:
            return self._lines + split_lines(self._partial, final=finished)

    def lines_with(self, text):
        return [line for line in self.lines() if text in line]

    def printed(self, text):
        """True once a complete line of its output contains text."""
        return bool(self.lines_with(text))

    def tail(self, lines=TAIL_LINES):
        """Its last output lines, as one text (for error messages)."""
        with self._lock:
            return '\n'.join((self._lines + split_lines(self._partial, final=True))[-lines:])

    def wait_line(self, text, timeout_s=EXIT_TIMEOUT_S):
        """Waits for an output line containing text and returns the first one; fails at once
        (with its last lines) if the process ends without printing it."""
        try:
            return wait_for(lambda: self.lines_with(text), timeout_s,
                            'output line %r of %s' % (text, self.name),
                            alive=lambda: not self._finished.is_set() or self.printed(text))[0]
        except WaitError as err:
            raise WaitError('%s; its last lines:\n%s' % (err, self.tail())) from None

    # --- its life ----------------------------------------------------------------------
    def alive(self):
        """True while the process started and has not ended."""
        return self.proc is not None and self.proc.poll() is None

    def exited(self):
        """True when the process was started and has ended."""
        return self.proc is not None and self.proc.poll() is not None

    def interrupt(self):
        """SIGINT to its session, as Ctrl-C in a terminal, without waiting."""
        if self.alive():
            self._signal_session(signal.SIGINT)

    def wait_exit(self, timeout_s=EXIT_TIMEOUT_S):
        """Waits for the process to end and returns its exit code; WaitError if it does not."""
        try:
            code = self.proc.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            raise WaitError('%s still running after %.0f s' % (self.name, timeout_s)) from None
        self._finished.wait(timeout_s)
        return code

    def stop(self, timeout_s=None):
        """SIGINT, then SIGKILL after timeout_s (default stop_timeout_s), to its session;
        idempotent. Returns the exit code: None if it never started or had to be killed."""
        if self._stopped or self.proc is None:
            return self._code
        self._stopped = True
        code = self.proc.poll()
        if code is None:
            self._signal_session(signal.SIGINT)
            try:
                code = self.proc.wait(self.stop_timeout_s if timeout_s is None else timeout_s)
            except subprocess.TimeoutExpired:
                code = None
        self._signal_session(signal.SIGKILL)  # also whatever it left behind
        self.proc.wait()
        self._finished.wait(self.stop_timeout_s)
        self._close_fds()
        self._code = code
        return code

    def close(self):
        self.stop()

    def _signal_session(self, sig):
        with contextlib.suppress(ProcessLookupError, PermissionError):  # it is empty already
            os.killpg(self.proc.pid, sig)

    def _close_fds(self):
        if self.terminal:
            for fd in (self._fd, self._slave):
                if fd is not None:
                    with contextlib.suppress(OSError):
                        os.close(fd)
            self._fd = self._slave = None
        elif self.proc.stdout is not None:
            self.proc.stdout.close()

    def __enter__(self):
        return self if self.proc is not None else self.start()

    def __exit__(self, *exc):
        self.stop()

    # --- a terminal's window -----------------------------------------------------------
    def send(self, data):
        """Types data (bytes) into the terminal."""
        os.write(self._fd, data)

    def terminal_lflags(self):
        """The terminal's local modes (termios lflag): what the process set, e.g. no ECHO."""
        return termios.tcgetattr(self._slave)[3]

    def hang_up(self):
        """Closes the terminal's master side, as when a terminal window is closed."""
        fd, self._fd = self._fd, None
        os.close(fd)


def spawn(argv, **kwargs):
    """A started ChildProcess of argv (keyword arguments as ChildProcess's)."""
    return ChildProcess(argv, **kwargs).start()


def run_to_exit(argv, timeout_s, **kwargs):
    """Runs argv to its end: (exit code, output); WaitError if it runs past timeout_s (then
    it is stopped). Keyword arguments as ChildProcess's."""
    with ChildProcess(argv, **kwargs) as proc:
        return proc.wait_exit(timeout_s), proc.output()
