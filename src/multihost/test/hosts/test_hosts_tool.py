"""./ws hosts: the namespaces it makes, that they reach each other, and that nothing stays."""
import atexit
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

import course_common.processes
import course_common.waiting
import pytest
from course_common.testing import spawn, wait_for

from multihost import hosts, netns

HOSTS = [sys.executable, '-m', 'multihost.hosts']


def _ws_hosts(*args, user=None, pythonpath=None):
    prefix = ['setpriv', '--reuid=%d' % user, '--regid=%d' % user, '--clear-groups'] if user else []
    env = dict(os.environ, ROS_HOME='/tmp')
    if pythonpath:
        env['PYTHONPATH'] = pythonpath
    return subprocess.run([*prefix, *HOSTS, *args], capture_output=True, text=True, env=env,
                          timeout=60, check=False)


def test_hosts_reach_each_other_by_name(team):
    status, out = team.run(2, [sys.executable, '-c', (
        'import socket; s = socket.socket(); s.bind(("10.77.0.2", 0)); s.listen();'
        'print(socket.gethostbyname("host3"), s.getsockname()[1])')])
    assert status == 0 and out.split()[0] == '10.77.0.3', out
    status, out = team.run(3, ['cat', '/etc/hosts'])
    assert '10.77.0.1\thost1' in out, out


def test_up_status_down_leave_nothing(hosts3):
    prefix = 'wsht%d' % os.getpid()
    left = None
    made = _ws_hosts('--prefix', prefix, 'up', '2')
    try:
        assert made.returncode == 0, made.stderr
        assert 'host2: namespace %s-h2, ROS_IP=10.77.0.2' % prefix in made.stdout
        assert sorted(netns.ours(prefix, hosts.list_namespaces())) == [
            prefix + '-h1', prefix + '-h2', prefix + '-sw']
        again = _ws_hosts('--prefix', prefix, 'up', '2')
        assert again.returncode == 1 and 'down first' in again.stderr
        status = _ws_hosts('--prefix', prefix, 'status')
        assert '%s-sw: switch, ports: p1 UP, p2 UP' % prefix in status.stdout, status.stdout
        missing = _ws_hosts('--prefix', prefix, 'exec', '3', 'true')
        assert missing.returncode == 1 and 'no host 3' in missing.stderr
        # A process left running in host 1 (as after `./ws hosts exec 1 roscore &`).
        left = spawn([*HOSTS, '--prefix', prefix, 'exec', '1', 'sleep', '300'])
        wait_for(lambda: subprocess.run(['ip', 'netns', 'pids', prefix + '-h1'],
                                        capture_output=True, text=True).stdout.strip(),
                 30.0, 'sleep to run in host 1')
    finally:
        gone = _ws_hosts('--prefix', prefix, 'down')
    assert left is not None and left.wait_exit(30) != 0  # down stopped it
    left.stop()
    assert gone.returncode == 0, gone.stderr
    assert netns.ours(prefix, hosts.list_namespaces()) == []
    assert not os.path.exists(os.path.join(netns.NETNS_ETC, prefix + '-h1'))


def test_not_root_says_so_in_one_line(hosts3):
    # An unprivileged user may not be able to read the checkout (a clone under a 0700 folder,
    # and pytest's tmp_path is 0700 too): give it a world-readable copy of the tool's modules.
    tmp_path = pathlib.Path(tempfile.mkdtemp(prefix='hosts_not_root_'))
    atexit.register(shutil.rmtree, tmp_path, ignore_errors=True)
    for module in (hosts, netns, course_common.processes, course_common.waiting):
        package = tmp_path / module.__name__.split('.')[0]
        package.mkdir(exist_ok=True)
        shutil.copy(module.__file__, package / os.path.basename(module.__file__))
        (package / '__init__.py').touch()
    for path in (tmp_path, *tmp_path.rglob('*')):
        path.chmod(0o755 if path.is_dir() else 0o644)
    result = _ws_hosts('up', '2', user=65534, pythonpath=str(tmp_path))
    assert result.returncode == 1
    assert result.stderr.strip().splitlines()[-1] == (
        'hosts: cannot run: network namespaces need root (run as root, or with sudo)')


def test_bad_count_is_refused(hosts3):
    result = _ws_hosts('--prefix', 'wshbad%d' % os.getpid(), 'up', '0')
    assert result.returncode == 1 and 'expected an integer from 1 to 50' in result.stderr


def test_namespaces_not_permitted_says_so_in_one_line(hosts3):
    """Root in a user namespace (like a container without CAP_SYS_ADMIN) may not mount
    /run/netns: one line naming the refused step."""
    if subprocess.run(['unshare', '-Ur', 'true'], capture_output=True, check=False).returncode:
        pytest.skip('this kernel does not allow user namespaces (unshare -Ur)')
    result = subprocess.run(['unshare', '-Ur', *HOSTS, 'up', '2'], capture_output=True,
                            text=True, timeout=60, check=False)
    assert result.returncode == 1
    assert result.stderr.strip().startswith("hosts: cannot run: 'ip netns add' is not permitted")
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr


def test_a_failed_up_removes_what_it_made(hosts3):
    prefix = 'wshf%d' % os.getpid()
    # Host 2's name is taken, so `up 3` fails half-way.
    subprocess.run(['ip', 'netns', 'add', netns.host_ns(prefix, 2)], check=True)
    try:
        with pytest.raises(hosts.HostsError, match='%s-h2' % prefix):
            hosts.Hosts(prefix, 3).up()
        assert netns.ours(prefix, hosts.list_namespaces()) == []
    finally:
        hosts.remove(prefix)
