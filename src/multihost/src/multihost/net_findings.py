"""What a host advertises in ROS URIs, and the fix for each network pitfall (no rospy, no IO).

ROS 1 nodes tell the master a URI naming their host; every other node connects to that name.
The name comes from ROS_HOSTNAME, else ROS_IP, else the machine's hostname (rosgraph's
get_host_name order). The classic failures: a name other hosts cannot resolve (nodes "see"
each other in `rostopic list` but receive nothing), a ROS_IP that is not this host's, a
loopback name (localhost) on a team, and a master that is not reachable. The functions here
turn facts gathered by ros_net_check.py into findings with the exact fix.
"""
import ipaddress
import urllib.parse
from dataclasses import dataclass

MASTER_DEFAULT_PORT = 11311


@dataclass(frozen=True)
class Finding:
    """One check: ok or not, what was seen, and (when not ok) the command or edit that fixes it."""

    ok: bool
    what: str
    fix: str = ''

    def lines(self):
        out = ['%s %s' % ('ok  ' if self.ok else 'FAIL', self.what)]
        if self.fix:
            out.append('     fix: ' + self.fix)
        return out


def is_address(text):
    try:
        ipaddress.ip_address(text)
    except ValueError:
        return False
    return True


def is_loopback(host):
    """True for names and addresses that mean "this machine" to whoever uses them."""
    if host == 'localhost' or host.startswith('localhost.'):
        return True
    return is_address(host) and ipaddress.ip_address(host).is_loopback


def advertised_host(env, hostname, local_addresses):
    """(host, source) this host puts in its ROS URIs, as rosgraph.network.get_host_name does.

    env: the environment (mapping); hostname: socket.gethostname(); local_addresses: this
    host's addresses. source is 'ROS_HOSTNAME', 'ROS_IP', 'hostname' or 'address'.
    """
    if env.get('ROS_HOSTNAME'):
        return env['ROS_HOSTNAME'], 'ROS_HOSTNAME'
    if env.get('ROS_IP'):
        return env['ROS_IP'], 'ROS_IP'
    if hostname and not is_loopback(hostname):
        return hostname, 'hostname'
    outside = team_addresses(local_addresses)
    return (outside[0] if outside else '127.0.0.1'), 'address'


def team_addresses(local_addresses):
    """The addresses other hosts could reach this one at: not loopback, not link-local."""
    return [a for a in local_addresses
            if is_address(a) and not ipaddress.ip_address(a).is_loopback
            and not ipaddress.ip_address(a).is_link_local]


def ros_ip_fix(local_addresses):
    """The exact `export ROS_IP=...` for this host, or a template when it has several."""
    outside = [a for a in team_addresses(local_addresses) if ipaddress.ip_address(a).version == 4]
    if len(outside) == 1:
        return 'export ROS_IP=%s' % outside[0]
    if outside:
        return ('export ROS_IP=<the address on the team network: one of %s>'
                % ', '.join(outside))
    return 'connect this host to the team network, then export ROS_IP=<its address there>'


def parse_master_uri(uri):
    """(host, port) of ROS_MASTER_URI; ValueError with the expected form when malformed."""
    parts = urllib.parse.urlparse(uri or '')
    try:
        port = parts.port
    except ValueError:
        port = -1
    if parts.scheme != 'http' or not parts.hostname or port == -1:
        raise ValueError('ROS_MASTER_URI=%r: expected http://HOST:PORT, e.g. http://host1:%d'
                         % (uri, MASTER_DEFAULT_PORT))
    return parts.hostname, port or MASTER_DEFAULT_PORT


def own_findings(host, source, resolved, local_addresses, master_remote):
    """Findings about the name this host advertises.

    resolved: the addresses `host` resolves to here (None: it does not resolve);
    master_remote: True when the master runs on another host (a team, not one machine).
    """
    fix = ros_ip_fix(local_addresses)
    shown = '%s=%s' % (source, host) if source in ('ROS_HOSTNAME', 'ROS_IP') else (
        'hostname %s' % host if source == 'hostname' else 'address %s' % host)
    if is_loopback(host):
        if master_remote:
            return [Finding(False, '%s is a loopback name: other hosts would connect to '
                            'themselves' % shown, (('unset %s; ' % source) if source in (
                                'ROS_HOSTNAME', 'ROS_IP') else '') + fix)]
        return [Finding(True, '%s: fine while every node runs on this machine' % shown)]
    if resolved is None:
        return [Finding(False, '%s does not resolve, even here: no node can reach this host'
                        % shown, fix)]
    if source == 'ROS_IP' and host not in local_addresses:
        return [Finding(False, 'ROS_IP=%s is not an address of this host (its addresses: %s)'
                        % (host, ', '.join(team_addresses(local_addresses)) or 'none'), fix)]
    own = set(local_addresses)
    if host in own:
        return [Finding(True, '%s is an address of this host' % shown)]
    if not any(a in own for a in resolved):
        return [Finding(False, '%s resolves here to %s, not to an address of this host'
                        % (shown, ', '.join(resolved)), fix)]
    findings = [Finding(True, '%s resolves here to %s' % (shown, ', '.join(resolved)))]
    if source != 'ROS_IP' and not is_address(host) and master_remote:
        findings.append(Finding(True, 'other hosts must resolve %r too (their /etc/hosts or DNS); '
                                'simplest: %s' % (host, fix)))
    return findings


def master_finding(uri, resolved, error, nodes):
    """The master check: error is None when its XML-RPC answered (nodes: how many nodes)."""
    host, port = parse_master_uri(uri)
    if resolved is None:
        return Finding(False, 'master host %r (ROS_MASTER_URI=%s) does not resolve' % (host, uri),
                       'export ROS_MASTER_URI=http://<address of the host running roscore>:%d'
                       % port)
    if error is not None:
        local = 'roscore runs on this host' if is_loopback(host) else (
            'roscore runs on %s and its firewall allows port %d' % (host, port))
        return Finding(False, 'master %s not reachable: %s' % (uri, error),
                       'check that %s, and that ROS_MASTER_URI names that host '
                       '(export ROS_MASTER_URI=http://<its address>:%d)' % (local, port))
    return Finding(True, 'master %s answers (nodes registered: %d)' % (uri, nodes))


def node_finding(node, uri, resolved, error):
    """A registered node's URI as seen from this host (resolved None: does not resolve)."""
    parts = urllib.parse.urlparse(uri)
    host = parts.hostname or ''
    if resolved is None:
        return Finding(False, 'node %s advertises %s but %r does not resolve here: '
                       'its topics are listed, but nothing it publishes arrives'
                       % (node, uri, host),
                       'on the host running %s: export ROS_IP=<its address> (and unset '
                       'ROS_HOSTNAME), or add "<its address> %s" to /etc/hosts on every host'
                       % (node, host))
    if error is not None:
        hint = (' (a loopback name: that host must export ROS_IP=<its address>)'
                if is_loopback(host) else '')
        return Finding(False, 'node %s at %s not reachable from here: %s%s'
                       % (node, uri, error, hint),
                       'on the host running %s: export ROS_IP=<its address on the team '
                       'network>; check its firewall' % node)
    return Finding(True, 'node %s at %s reachable' % (node, uri))
