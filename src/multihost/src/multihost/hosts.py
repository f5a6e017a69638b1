"""N hosts on one machine: create, use and remove the network namespaces of netns.py.

Command line (./ws hosts ...; needs root and iproute2's `ip netns`):
    up N        create the switch and hosts 1..N (host i is 10.77.0.<i>, named host<i>)
    down        stop what runs inside, remove every namespace of the prefix (--stale: also
                leftovers of test runs whose process is gone)
    status      list the prefix's namespaces and each host's address and link state
    exec I CMD  run CMD in host I with ROS_IP=<its address>, ROS_MASTER_URI=http://host 1:11311
    link I up|down   plug in / pull out host I's cable (its switch port)
    netem ARGS | netem off   tc netem on every switch port, e.g. netem delay 20ms loss 1%
"""
import argparse
import contextlib
import os
import shutil
import signal
import subprocess
import sys
import time

from course_common.processes import pid_running

from multihost import netns

MASTER_PORT = 11311  # each namespace has its own ports: the standard one never collides
STOP_WAIT_S = 5.0  # processes left in a namespace get this long after SIGTERM, then SIGKILL


class HostsError(RuntimeError):
    """A command needed for the hosts failed, or the machine cannot make namespaces."""


def _run(argv, check=True):
    result = subprocess.run(argv, capture_output=True, text=True, check=False)
    if check and result.returncode != 0:
        raise HostsError('%s: %s' % (' '.join(argv), (result.stderr or result.stdout).strip()))
    return result


def unavailable_reason():
    """None when this process can make network namespaces, else a one-line reason."""
    if os.geteuid() != 0:
        return 'network namespaces need root (run as root, or with sudo)'
    if shutil.which('ip') is None:
        return "no 'ip' command (install iproute2)"
    probe = 'wshprobe%d-sw' % os.getpid()
    made = _run(['ip', 'netns', 'add', probe], check=False)
    if made.returncode != 0:
        return "'ip netns add' is not permitted here (%s)" % made.stderr.strip()
    _run(['ip', 'netns', 'del', probe], check=False)
    return None


def list_namespaces():
    return netns.parse_netns_list(_run(['ip', 'netns', 'list']).stdout)


def master_uri():
    return 'http://%s:%d' % (netns.host_address(1), MASTER_PORT)


def host_env(i, base=None):
    """The environment of a process on host i: its ROS_IP, the master on host 1."""
    env = dict(os.environ if base is None else base)
    env.pop('ROS_HOSTNAME', None)  # it would win over ROS_IP (and ./ws sets localhost)
    env['ROS_IP'] = netns.host_address(i)
    env['ROS_MASTER_URI'] = master_uri()
    return env


class Hosts:
    """The namespaces of one prefix; `with Hosts(prefix, n) as hosts:` removes them at exit."""

    def __init__(self, prefix, n):
        self.prefix = netns.check_prefix(prefix)
        self.n = netns.check_count(n)

    def __enter__(self):
        self.up()
        return self

    def __exit__(self, *exc):
        self.down()

    def up(self):
        """Create the switch and the hosts; on any failure remove what was made, then raise."""
        try:
            for argv in netns.up_commands(self.prefix, self.n):
                _run(argv)
            for i in range(1, self.n + 1):
                directory = os.path.join(netns.NETNS_ETC, netns.host_ns(self.prefix, i))
                os.makedirs(directory, exist_ok=True)
                with open(os.path.join(directory, 'hosts'), 'w', encoding='utf-8') as f:
                    f.write(netns.hosts_file(self.n))
        except BaseException:
            self.down()
            raise

    def down(self):
        remove(self.prefix)

    def ns(self, i):
        return netns.host_ns(self.prefix, i)

    def argv(self, i, command):
        """argv running command (a list) inside host i."""
        return ['ip', 'netns', 'exec', self.ns(i), *command]

    def link(self, i, up):
        _run(netns.link_command(self.prefix, i, up))

    def netem(self, args):
        """Put netem args on every switch port ([] removes them); HostsError if refused."""
        for argv in netns.netem_commands(self.prefix, self.n, list(args)):
            _run(argv)


def _stop_processes(names):
    """SIGTERM, then SIGKILL, the processes still running inside the namespaces names.

    A namespace outlives `ip netns del` while a process holds it (a roscore left running
    by a killed test run); only processes inside these namespaces are signalled.
    """
    pids = set()
    for name in names:
        pids.update(int(p) for p in _run(['ip', 'netns', 'pids', name], check=False).stdout.split())
    deadline = time.monotonic() + STOP_WAIT_S
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for pid in pids:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, sig)
        while pids and time.monotonic() < deadline:
            pids = {pid for pid in pids if pid_running(pid)}
            time.sleep(0.05)
        deadline = time.monotonic() + STOP_WAIT_S


def remove(prefix):
    """Stop the processes inside the namespaces of prefix, remove them and their /etc/netns
    directories; never raises for one of them."""
    names = netns.ours(prefix, list_namespaces())
    _stop_processes(names)
    for name in names:
        _run(['ip', 'netns', 'del', name], check=False)
        shutil.rmtree(os.path.join(netns.NETNS_ETC, name), ignore_errors=True)


def _status(prefix):
    names = netns.ours(prefix, list_namespaces())
    if not names:
        print('hosts: no namespaces with prefix %s' % prefix)
        return
    for name in sorted(names):
        if name.endswith('-sw'):
            ports = _run(['ip', '-n', name, '-br', 'link', 'show', 'master', netns.BRIDGE],
                         check=False).stdout.split('\n')
            print('%s: switch, ports: %s' % (name, ', '.join(
                '%s %s' % (p.split()[0].split('@')[0], p.split()[1]) for p in ports if p.strip())))
        else:
            addr = _run(['ip', '-n', name, '-br', 'addr', 'show', netns.HOST_IFACE],
                        check=False).stdout.split()
            print('%s: %s' % (name, ' '.join(addr) or '(no %s)' % netns.HOST_IFACE))


def _parser():
    parser = argparse.ArgumentParser(prog='./ws hosts', description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--prefix', default=netns.DEFAULT_PREFIX,
                        help='namespace name prefix (default %(default)s)')
    sub = parser.add_subparsers(dest='command', required=True)
    sub.add_parser('up').add_argument('n', type=int)
    down = sub.add_parser('down')
    down.add_argument('--stale', action='store_true',
                      help="also remove test runs' leftovers whose process is gone")
    sub.add_parser('status')
    ex = sub.add_parser('exec')
    ex.add_argument('i', type=int)
    ex.add_argument('cmd', nargs=argparse.REMAINDER)
    link = sub.add_parser('link')
    link.add_argument('i', type=int)
    link.add_argument('state', choices=['up', 'down'])
    netem = sub.add_parser('netem')
    netem.add_argument('args', nargs=argparse.REMAINDER, help="netem options, or 'off'")
    return parser


def _count_hosts(prefix):
    return sum(1 for name in netns.ours(prefix, list_namespaces()) if not name.endswith('-sw'))


def _interrupted(signum, _frame):
    raise KeyboardInterrupt('signal %d' % signum)


def run(argv=None):
    """The command line; returns the exit status."""
    args = _parser().parse_args(argv)
    reason = unavailable_reason()
    if reason:
        print('hosts: cannot run: %s' % reason, file=sys.stderr)
        return 1
    # SIGTERM unwinds like Ctrl-C, so a half-made `up` is removed.
    signal.signal(signal.SIGTERM, _interrupted)
    try:
        if args.command == 'up':
            if netns.ours(args.prefix, list_namespaces()):
                print('hosts: namespaces with prefix %s exist: ./ws hosts down first'
                      % args.prefix, file=sys.stderr)
                return 1
            Hosts(args.prefix, netns.check_count(args.n)).up()
            for i in range(1, args.n + 1):
                print('host%d: namespace %s, ROS_IP=%s' % (
                    i, netns.host_ns(args.prefix, i), netns.host_address(i)))
            print('master (on host1): ROS_MASTER_URI=%s' % master_uri())
        elif args.command == 'down':
            remove(args.prefix)
            if args.stale:
                for prefix in netns.stale_prefixes(list_namespaces(), pid_running):
                    remove(prefix)
        elif args.command == 'status':
            _status(args.prefix)
        elif args.command == 'exec':
            if not args.cmd:
                print('hosts: exec needs a command', file=sys.stderr)
                return 2
            if not 1 <= args.i <= _count_hosts(args.prefix):
                print('hosts: no host %d (./ws hosts status)' % args.i, file=sys.stderr)
                return 1
            command = ['ip', 'netns', 'exec', netns.host_ns(args.prefix, args.i), *args.cmd]
            os.execvpe('ip', command, host_env(args.i))
        elif args.command == 'link':
            _run(netns.link_command(args.prefix, args.i, args.state == 'up'))
        elif args.command == 'netem':
            n = _count_hosts(args.prefix)
            off = args.args in ([], ['off'])
            for command in netns.netem_commands(args.prefix, netns.check_count(n),
                                                [] if off else args.args):
                _run(command, check=not off)
    except (ValueError, HostsError) as err:
        print('hosts: %s' % err, file=sys.stderr)
        return 1
    return 0


def main(argv=None):
    """./ws hosts COMMAND ... (rosrun multihost hosts)."""
    sys.exit(run(argv))


if __name__ == '__main__':
    main()
