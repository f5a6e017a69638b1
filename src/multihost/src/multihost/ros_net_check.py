"""ros_net_check: the ROS URIs this host advertises and whether the team can reach each other.

Usage: rosrun multihost ros_net_check [--hosts NAME ...] [--timeout S]

Prints, for this host: the name it puts in its URIs (from ROS_HOSTNAME / ROS_IP / hostname)
and whether it is really this host's; whether the master (ROS_MASTER_URI) answers; for every
node registered with the master, whether its URI resolves and connects from here; and each
--hosts name resolves. Every failure comes with the exact fix. Exit status 1 when something
fails. It does not register a node itself: it only asks the master.
"""
import argparse
import os
import socket
import sys
import urllib.parse

import netifaces
import rosgraph

from multihost import net_findings

TIMEOUT_S = 2.0  # per connection attempt: a LAN answers in milliseconds
MAX_NODES = 200  # bounds the run on a large graph


def local_addresses():
    addrs = []
    for iface in netifaces.interfaces():
        for family in (socket.AF_INET, socket.AF_INET6):
            addrs += [a['addr'].split('%')[0]
                      for a in netifaces.ifaddresses(iface).get(family, [])]
    return addrs


def resolve(host):
    """Addresses host resolves to here, or None."""
    try:
        infos = socket.getaddrinfo(host, None, socket.AF_INET, socket.SOCK_STREAM)
    except (OSError, UnicodeError):
        return None
    return sorted({info[4][0] for info in infos}) or None


def connect_error(host, port, timeout_s):
    """None when a TCP connection to host:port succeeds, else why not."""
    try:
        with socket.create_connection((host, port), timeout=timeout_s):
            return None
    except TimeoutError:
        return 'no answer within %.1f s (host down, cable out, or a firewall)' % timeout_s
    except OSError as err:
        return err.strerror or str(err)


def master_nodes(uri):
    """{node name: URI} of every node the master knows."""
    master = rosgraph.Master('/ros_net_check', master_uri=uri)
    names = set()
    for group in master.getSystemState():
        for _topic, nodes in group:
            names.update(nodes)
    found = {}
    for name in sorted(names)[:MAX_NODES]:
        try:
            found[name] = master.lookupNode(name)
        except rosgraph.MasterError:
            continue  # it left meanwhile
    return found


def check(env, hosts, timeout_s):
    """(header lines, findings) for this host."""
    addrs = local_addresses()
    host, source = net_findings.advertised_host(env, socket.gethostname(), addrs)
    uri = env.get('ROS_MASTER_URI', '')
    header = ['this host advertises http://%s:<port>/ (from %s)' % (host, source),
              'its addresses: %s' % (', '.join(net_findings.team_addresses(addrs))
                                     or 'loopback only')]
    try:
        master_host, master_port = net_findings.parse_master_uri(uri)
    except ValueError as err:
        fix = ('export ROS_MASTER_URI=http://<host running roscore>:%d'
               % net_findings.MASTER_DEFAULT_PORT)
        return header, [net_findings.Finding(False, str(err), fix)]
    master_resolved = resolve(master_host)
    master_remote = not (net_findings.is_loopback(master_host) or (
        master_resolved is not None and set(master_resolved) & set(addrs)))
    findings = net_findings.own_findings(host, source, resolve(host), addrs, master_remote)
    nodes, error = {}, None
    if master_resolved is not None:
        error = connect_error(master_host, master_port, timeout_s)
        if error is None:
            try:
                nodes = master_nodes(uri)
            except (OSError, rosgraph.MasterError) as err:
                error = 'its XML-RPC failed: %s' % err
    findings.append(net_findings.master_finding(uri, master_resolved, error, len(nodes)))
    for name, node_uri in nodes.items():
        parts = urllib.parse.urlparse(node_uri)
        resolved = resolve(parts.hostname or '')
        node_error = None if resolved is None else connect_error(
            parts.hostname, parts.port, timeout_s)
        findings.append(net_findings.node_finding(name, node_uri, resolved, node_error))
    for name in hosts:
        resolved = resolve(name)
        findings.append(net_findings.Finding(True, 'host %s resolves to %s' % (name, ', '.join(
            resolved))) if resolved else net_findings.Finding(
            False, 'host %s does not resolve here' % name,
            'add "<its address> %s" to /etc/hosts (or use addresses: ROS_IP on every host)'
            % name))
    return header, findings


def run(argv=None):
    parser = argparse.ArgumentParser(prog='ros_net_check', description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--hosts', nargs='*', default=[], help='other hosts of the team')
    parser.add_argument('--timeout', type=float, default=TIMEOUT_S,
                        help='seconds per connection attempt (default %(default)s)')
    args = parser.parse_args(argv)
    if not 0 < args.timeout <= 60:
        parser.error('--timeout %s: expected seconds in (0, 60]' % args.timeout)
    socket.setdefaulttimeout(args.timeout)  # also bounds the master's XML-RPC calls
    header, findings = check(os.environ, args.hosts, args.timeout)
    print('ros_net_check: ' + header[0])
    for line in header[1:]:
        print('  ' + line)
    for finding in findings:
        for line in finding.lines():
            print('  ' + line)
    failed = sum(not f.ok for f in findings)
    print('ros_net_check: %s' % ('all ok' if not failed else '%d problem(s)' % failed))
    return 1 if failed else 0


def main(argv=None):
    """rosrun multihost ros_net_check [--hosts NAME ...]."""
    sys.exit(run(argv))
