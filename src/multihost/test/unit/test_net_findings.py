"""Unit tests of multihost.net_findings: advertised names, each pitfall's finding and fix."""
import pytest

from multihost import net_findings

HOST2 = ['127.0.0.1', '10.77.0.2', '::1', 'fe80::1']


@pytest.mark.parametrize(('env', 'hostname', 'expected'), [
    ({'ROS_HOSTNAME': 'ghost', 'ROS_IP': '10.77.0.2'}, 'laptop', ('ghost', 'ROS_HOSTNAME')),
    ({'ROS_IP': '10.77.0.2'}, 'laptop', ('10.77.0.2', 'ROS_IP')),
    ({'ROS_HOSTNAME': '', 'ROS_IP': '10.77.0.2'}, 'laptop', ('10.77.0.2', 'ROS_IP')),
    ({}, 'laptop', ('laptop', 'hostname')),
    ({}, 'localhost', ('10.77.0.2', 'address')),   # rosgraph falls back to an address
    ({}, '', ('10.77.0.2', 'address')),
])
def test_advertised_host_follows_rosgraph_order(env, hostname, expected):
    assert net_findings.advertised_host(env, hostname, HOST2) == expected


def test_advertised_host_loopback_only():
    assert net_findings.advertised_host({}, 'localhost', ['127.0.0.1']) == ('127.0.0.1', 'address')


@pytest.mark.parametrize(('host', 'loopback'), [
    ('localhost', True), ('127.0.0.1', True), ('127.0.1.1', True), ('::1', True),
    ('localhost.localdomain', True), ('10.77.0.1', False), ('host1', False), ('localhostx', False),
])
def test_is_loopback(host, loopback):
    assert net_findings.is_loopback(host) is loopback


@pytest.mark.parametrize(('addrs', 'fix'), [
    (HOST2, 'export ROS_IP=10.77.0.2'),
    (['127.0.0.1', '10.77.0.2', '192.168.1.5'],
     'export ROS_IP=<the address on the team network: one of 10.77.0.2, 192.168.1.5>'),
    (['127.0.0.1'],
     'connect this host to the team network, then export ROS_IP=<its address there>'),
])
def test_ros_ip_fix(addrs, fix):
    assert net_findings.ros_ip_fix(addrs) == fix


@pytest.mark.parametrize(('uri', 'expected'), [
    ('http://host1:11311', ('host1', 11311)),
    ('http://10.77.0.1:12000/', ('10.77.0.1', 12000)),
    ('http://host1', ('host1', 11311)),
])
def test_parse_master_uri(uri, expected):
    assert net_findings.parse_master_uri(uri) == expected


@pytest.mark.parametrize('uri', ['', None, 'host1:11311', 'https://host1:11311', 'http://:11311',
                                 'http://host1:port'])
def test_parse_master_uri_rejects(uri):
    with pytest.raises(ValueError, match='expected http://HOST:PORT'):
        net_findings.parse_master_uri(uri)


@pytest.mark.parametrize(('host', 'source', 'resolved', 'remote', 'ok', 'what', 'fix'), [
    # the team's good case: an address of this host
    ('10.77.0.2', 'ROS_IP', ['10.77.0.2'], True, True,
     'ROS_IP=10.77.0.2 is an address of this', ''),
    # a hostname that resolves to this host
    ('laptop', 'hostname', ['10.77.0.2'], False, True,
     'hostname laptop resolves here to 10.77.0.2', ''),
    # wrong ROS_IP (another host's, or a typo)
    ('10.77.0.9', 'ROS_IP', ['10.77.0.9'], True, False,
     'ROS_IP=10.77.0.9 is not an address of this host (its addresses: 10.77.0.2',
     'export ROS_IP=10.77.0.2'),
    # a name no one can resolve
    ('ghost', 'ROS_HOSTNAME', None, True, False, 'ROS_HOSTNAME=ghost does not resolve',
     'export ROS_IP=10.77.0.2'),
    # localhost on a team: other hosts would call themselves
    ('localhost', 'ROS_HOSTNAME', ['127.0.0.1'], True, False, 'loopback name',
     'unset ROS_HOSTNAME; export ROS_IP=10.77.0.2'),
    # localhost with everything on one machine: fine
    ('localhost', 'ROS_HOSTNAME', ['127.0.0.1'], False, True, 'fine while every node', ''),
    # a hostname that resolves elsewhere (stale /etc/hosts entry)
    ('laptop', 'hostname', ['10.77.0.7'], True, False,
     'resolves here to 10.77.0.7, not to an address',
     'export ROS_IP=10.77.0.2'),
])
def test_own_findings(host, source, resolved, remote, ok, what, fix):
    first = net_findings.own_findings(host, source, resolved, HOST2, remote)[0]
    assert first.ok is ok
    assert what in first.what
    assert first.fix == fix


def test_own_hostname_reminds_that_others_must_resolve_it():
    findings = net_findings.own_findings('laptop', 'hostname', ['10.77.0.2'], HOST2, True)
    assert [f.ok for f in findings] == [True, True]
    assert "other hosts must resolve 'laptop'" in findings[1].what


@pytest.mark.parametrize(('uri', 'resolved', 'error', 'ok', 'what', 'fix'), [
    ('http://host1:11311', ['10.77.0.1'], None, True, 'answers (nodes registered: 5)', ''),
    ('http://nohost:11311', None, None, False, "'nohost'", 'export ROS_MASTER_URI=http://<address'),
    ('http://host1:11311', ['10.77.0.1'], 'Connection refused', False,
     'not reachable: Connection refused', 'roscore runs on host1'),
    ('http://localhost:11311', ['127.0.0.1'], 'Connection refused', False,
     'not reachable', 'roscore runs on this host'),
])
def test_master_finding(uri, resolved, error, ok, what, fix):
    finding = net_findings.master_finding(uri, resolved, error, 5)
    assert finding.ok is ok
    assert what in finding.what
    assert fix in finding.fix


@pytest.mark.parametrize(('uri', 'resolved', 'error', 'ok', 'what', 'fix'), [
    ('http://10.77.0.3:4000/', ['10.77.0.3'], None, True, 'reachable', ''),
    ('http://ghost:4000/', None, None, False, "'ghost' does not resolve here",
     'add "<its address> ghost" to /etc/hosts'),
    ('http://localhost:4000/', ['127.0.0.1'], 'Connection refused', False, 'a loopback name',
     'export ROS_IP'),
    ('http://10.77.0.3:4000/', ['10.77.0.3'], 'no answer', False, 'not reachable from here',
     'export ROS_IP'),
])
def test_node_finding(uri, resolved, error, ok, what, fix):
    finding = net_findings.node_finding('/robot', uri, resolved, error)
    assert finding.ok is ok
    assert what in finding.what
    assert fix in finding.fix


def test_finding_lines():
    assert net_findings.Finding(True, 'good').lines() == ['ok   good']
    assert net_findings.Finding(False, 'bad', 'do x').lines() == ['FAIL bad', '     fix: do x']
