"""Everything the desktop started, found and stopped: its whole process tree.

What a student starts in the desktop's terminals does not stay in one process group:
roslaunch puts each node in a session of its own, and `roscore &` in a terminal that was
then closed leaves an orphan. So the desktop makes itself a child subreaper (Linux's
PR_SET_CHILD_SUBREAPER): orphans of its tree are re-parented to it, not to init, and its tree
by parent pids (course_common.processes.descendants) holds everything it ever started that
still runs. Stopping sends SIGTERM to all of it (a background job of a non-interactive bash
ignores SIGINT; rospy, roslaunch, Xvnc and xterm all end cleanly on SIGTERM), then SIGKILL to
what is left after a grace period.
"""
import contextlib
import ctypes
import glob
import os
import signal
import time

from course_common.processes import descendants, pid_running, process_table

PR_SET_CHILD_SUBREAPER = 36  # <linux/prctl.h>
STOP_GRACE_S = 10.0  # roslaunch gives its nodes this long for SIGINT before escalating
POLL_S = 0.05


def become_subreaper():
    """Orphans of this process's tree come to it (Linux 3.4+); False where prctl fails."""
    libc = ctypes.CDLL(None, use_errno=True)
    return libc.prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0


def tree(root=None):
    """The pids under root (this process by default), root itself left out."""
    root = os.getpid() if root is None else root
    return [pid for pid in descendants(root, process_table()) if pid != root]


def children():
    """The pids of this process's children, from the kernel's list per thread (cheap: the
    idle desktop calls this every second; the whole process table would cost it 100 times
    more with a lesson running)."""
    pids = set()
    for path in glob.glob('/proc/self/task/*/children'):
        try:
            with open(path, encoding='ascii') as f:
                pids.update(int(p) for p in f.read().split())
        except OSError:
            continue
    return pids


def reap_orphans(known=()):
    """Collects the exit status of children this process did not start itself (orphans
    re-parented to it), so none stays a zombie; `known` are children whose Popen waits for
    them. Returns how many it reaped."""
    reaped = 0
    for pid in children() - set(known):
        with contextlib.suppress(ChildProcessError):
            done, _ = os.waitpid(pid, os.WNOHANG)
            reaped += bool(done)
    return reaped


def stop_tree(known=(), grace_s=STOP_GRACE_S, root=None):
    """SIGTERM to every process under root, SIGKILL to the survivors after grace_s; waits
    until none is left (orphans reaped as they end). Returns the pids that had to be killed."""
    _signal_all(tree(root), signal.SIGTERM)
    deadline = time.monotonic() + grace_s
    while time.monotonic() < deadline:
        reap_orphans(known)
        if not running(tree(root)):
            return []
        time.sleep(POLL_S)
    stubborn = running(tree(root))
    _signal_all(stubborn, signal.SIGKILL)
    deadline = time.monotonic() + grace_s
    while running(tree(root)) and time.monotonic() < deadline:
        reap_orphans(known)
        time.sleep(POLL_S)
    return stubborn


def _signal_all(pids, sig):
    for pid in pids:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, sig)


def running(pids):
    """Those of pids that still run (course_common.processes.pid_running)."""
    return [pid for pid in pids if pid_running(pid)]
