"""course_desktop.reaper: the whole tree stopped, orphans and other sessions included.

Run in a child Python of its own: making pytest's process a subreaper would hand it every
orphan of the rest of the test run.
"""
import os
import subprocess
import sys
import textwrap

from course_common.processes import pid_running

SCRIPT = textwrap.dedent('''
    import os, subprocess, sys, time
    from course_desktop import reaper
    assert reaper.become_subreaper()
    # A background job, a job in a session of its own, and an orphan (its parent exits).
    shell = subprocess.Popen(['bash', '-c', 'sleep 301 & setsid sleep 302 & (sleep 303 &); wait'])
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        names = [open('/proc/%d/cmdline' % p).read() for p in reaper.tree() if
                 os.path.exists('/proc/%d/cmdline' % p)]
        if sum(n.startswith('sleep\\0') for n in names) == 3:
            break
        time.sleep(0.05)
    pids = reaper.tree()
    print(' '.join(map(str, pids)), flush=True)
    killed = reaper.stop_tree(known={shell.pid}, grace_s=10)
    shell.wait()
    print('left', len(reaper.running(reaper.tree())), 'killed', len(killed), flush=True)
''')


def test_stop_tree_ends_background_jobs_other_sessions_and_orphans():
    done = subprocess.run([sys.executable, '-c', SCRIPT], capture_output=True, text=True,
                          timeout=60, env=dict(os.environ))
    assert done.returncode == 0, done.stderr
    first, last = done.stdout.strip().splitlines()
    pids = [int(p) for p in first.split()]
    assert len(pids) >= 4  # bash and its three sleeps
    assert last == 'left 0 killed 0'  # SIGTERM was enough for all of them
    assert not [pid for pid in pids if pid_running(pid)]


def test_children_are_this_process_children_only():
    from course_desktop.reaper import children
    child = subprocess.Popen(['sleep', '30'])
    try:
        assert child.pid in children()
        assert os.getpid() not in children()
    finally:
        child.kill()
        child.wait()
    assert child.pid not in children()
