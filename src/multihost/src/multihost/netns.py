"""Plans for N hosts on one machine as network namespaces (no subprocess, no rospy).

The layout: one "switch" namespace holds a bridge; each host namespace is joined to it by a
veth pair (port p<i> in the switch, eth0 in host i), has its own loopback, the address
SUBNET.<i> and a hosts file naming every host (ip netns exec bind-mounts
/etc/netns/<namespace>/hosts over /etc/hosts). Nothing is created in the caller's own
network namespace, so the machine's real network is never touched.
"""
import ipaddress
import re

SUBNET = ipaddress.IPv4Network('10.77.0.0/24')  # private; exists only inside the namespaces
MAX_HOSTS = 50  # every host is a full set of ROS processes: more would not fit a laptop
DEFAULT_PREFIX = 'wsh'
HOST_IFACE = 'eth0'
BRIDGE = 'br0'
NETNS_ETC = '/etc/netns'
# Namespace names become file names under /run/netns and /etc/netns.
_PREFIX_RE = re.compile(r'^[a-z][a-z0-9]{0,15}$')
# A namespace of a test run: the prefix is DEFAULT_PREFIX plus that run's process id.
_RUN_NS_RE = re.compile(r'^%s(\d+)-' % DEFAULT_PREFIX)


def check_prefix(prefix):
    """Return prefix if it can name namespaces; raise ValueError otherwise."""
    if not isinstance(prefix, str) or not _PREFIX_RE.match(prefix):
        raise ValueError('prefix %r: expected a lower-case letter then up to 15 letters or '
                         'digits' % (prefix,))
    return prefix


def check_count(n):
    """Return n if it is a valid number of hosts (1..MAX_HOSTS); raise ValueError otherwise."""
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_HOSTS:
        raise ValueError('number of hosts %r: expected an integer from 1 to %d' % (n, MAX_HOSTS))
    return n


def switch_ns(prefix):
    """The namespace holding the bridge."""
    return '%s-sw' % check_prefix(prefix)


def host_ns(prefix, i):
    """The namespace standing in for host i (1-based)."""
    return '%s-h%d' % (check_prefix(prefix), i)


def host_name(i):
    """Host i's name in every host's hosts file."""
    return 'host%d' % i


def host_address(i):
    """Host i's address: SUBNET.<i>."""
    if isinstance(i, bool) or not isinstance(i, int) or not 1 <= i <= MAX_HOSTS:
        raise ValueError('host %r: expected an integer from 1 to %d' % (i, MAX_HOSTS))
    return str(SUBNET.network_address + i)


def switch_port(i):
    """Host i's port on the switch (the switch end of its veth pair)."""
    return 'p%d' % i


def hosts_file(n):
    """The /etc/hosts of every host: loopback names, then host1..hostN."""
    lines = ['127.0.0.1\tlocalhost', '::1\tlocalhost ip6-localhost ip6-loopback']
    lines += ['%s\t%s' % (host_address(i), host_name(i)) for i in range(1, check_count(n) + 1)]
    return '\n'.join(lines) + '\n'


def up_commands(prefix, n):
    """The `ip` commands (argv lists) that build the switch and n hosts, in order."""
    check_count(n)
    sw = switch_ns(prefix)
    cmds = [['ip', 'netns', 'add', sw],
            ['ip', '-n', sw, 'link', 'set', 'lo', 'up'],
            ['ip', '-n', sw, 'link', 'add', BRIDGE, 'type', 'bridge'],
            ['ip', '-n', sw, 'link', 'set', BRIDGE, 'up']]
    for i in range(1, n + 1):
        ns = host_ns(prefix, i)
        port = switch_port(i)
        cmds += [['ip', 'netns', 'add', ns],
                 # Both ends are created directly inside their namespaces.
                 ['ip', 'link', 'add', port, 'netns', sw, 'type', 'veth',
                  'peer', 'name', HOST_IFACE, 'netns', ns],
                 ['ip', '-n', sw, 'link', 'set', port, 'master', BRIDGE],
                 ['ip', '-n', sw, 'link', 'set', port, 'up'],
                 ['ip', '-n', ns, 'link', 'set', 'lo', 'up'],
                 ['ip', '-n', ns, 'addr', 'add', '%s/%d' % (host_address(i), SUBNET.prefixlen),
                  'dev', HOST_IFACE],
                 ['ip', '-n', ns, 'link', 'set', HOST_IFACE, 'up']]
    return cmds


def link_command(prefix, i, up):
    """Plug host i's cable back in (up) or pull it out (down), at the switch port."""
    host_address(i)
    return ['ip', '-n', switch_ns(prefix), 'link', 'set', switch_port(i),
            'up' if up else 'down']


def netem_commands(prefix, n, netem_args):
    """tc commands putting netem (e.g. ['delay', '20ms', 'loss', '1%']) on every switch port.

    A packet from one host to another leaves the switch through one port, so it is delayed
    once per direction. An empty netem_args removes the qdiscs instead.
    """
    check_count(n)
    sw = switch_ns(prefix)
    if not netem_args:
        return [['ip', 'netns', 'exec', sw, 'tc', 'qdisc', 'del', 'dev', switch_port(i), 'root']
                for i in range(1, n + 1)]
    return [['ip', 'netns', 'exec', sw, 'tc', 'qdisc', 'replace', 'dev', switch_port(i),
             'root', 'netem', *netem_args] for i in range(1, n + 1)]


def ours(prefix, namespaces):
    """The namespaces (names) that belong to prefix: '<prefix>-sw' and '<prefix>-h<i>'."""
    pattern = re.compile(r'^%s-(sw|h\d+)$' % re.escape(check_prefix(prefix)))
    return [ns for ns in namespaces if pattern.match(ns)]


def stale_prefixes(namespaces, alive):
    """Prefixes of test runs ('wsh<pid>') whose process is gone (alive(pid) is False)."""
    found = set()
    for ns in namespaces:
        match = _RUN_NS_RE.match(ns)
        if match and not alive(int(match.group(1))):
            found.add('%s%s' % (DEFAULT_PREFIX, match.group(1)))
    return sorted(found)


def parse_netns_list(text):
    """Namespace names from `ip netns list` output ('name' or 'name (id: 3)' per line)."""
    return [line.split()[0] for line in text.splitlines() if line.strip()]
