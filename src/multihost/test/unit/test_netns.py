"""Unit tests of multihost.netns: names, addresses, the ip/tc command plans."""
import pytest

from multihost import netns


@pytest.mark.parametrize('prefix', ['wsh', 'wsh1234', 'a', 'abcdefghijklmnop'])
def test_good_prefixes(prefix):
    assert netns.check_prefix(prefix) == prefix


@pytest.mark.parametrize('prefix', ['', 'Wsh', '1wsh', 'ws-h', 'ws h', 'abcdefghijklmnopq',
                                    None, 3])
def test_bad_prefixes(prefix):
    with pytest.raises(ValueError, match='prefix'):
        netns.check_prefix(prefix)


@pytest.mark.parametrize('n', [0, -1, netns.MAX_HOSTS + 1, 2.0, True, '3'])
def test_bad_counts(n):
    with pytest.raises(ValueError, match='number of hosts'):
        netns.check_count(n)


@pytest.mark.parametrize(('i', 'address'), [(1, '10.77.0.1'), (3, '10.77.0.3'),
                                            (netns.MAX_HOSTS, '10.77.0.%d' % netns.MAX_HOSTS)])
def test_host_address(i, address):
    assert netns.host_address(i) == address


@pytest.mark.parametrize('i', [0, netns.MAX_HOSTS + 1, '1', True])
def test_bad_host_address(i):
    with pytest.raises(ValueError, match='host'):
        netns.host_address(i)


def test_names():
    assert netns.switch_ns('wsh7') == 'wsh7-sw'
    assert netns.host_ns('wsh7', 2) == 'wsh7-h2'
    assert netns.host_name(2) == 'host2'
    assert netns.switch_port(2) == 'p2'


def test_hosts_file_names_every_host_and_localhost():
    lines = netns.hosts_file(3).splitlines()
    assert lines[0] == '127.0.0.1\tlocalhost'
    assert lines[-3:] == ['10.77.0.1\thost1', '10.77.0.2\thost2', '10.77.0.3\thost3']


def test_up_commands_never_touch_the_callers_namespace():
    """Every command names a namespace: either `ip -n NS`, `ip netns add`, or a veth pair
    created with both ends inside namespaces."""
    cmds = netns.up_commands('wsh1', 2)
    for argv in cmds:
        assert argv[0] == 'ip'
        if argv[1] == '-n':
            assert argv[2] in ('wsh1-sw', 'wsh1-h1', 'wsh1-h2')
        elif argv[1:3] == ['netns', 'add']:
            continue
        else:
            assert argv[1:3] == ['link', 'add']
            assert argv[argv.index('netns') + 1] == 'wsh1-sw'
            assert argv[-2:][0] == 'netns' and argv[-1].startswith('wsh1-h')
    assert cmds[0] == ['ip', 'netns', 'add', 'wsh1-sw']
    assert ['ip', '-n', 'wsh1-h2', 'addr', 'add', '10.77.0.2/24', 'dev', 'eth0'] in cmds


def test_link_command_pulls_the_switch_port():
    assert netns.link_command('wsh1', 3, up=False) == [
        'ip', '-n', 'wsh1-sw', 'link', 'set', 'p3', 'down']
    assert netns.link_command('wsh1', 3, up=True)[-1] == 'up'
    with pytest.raises(ValueError):
        netns.link_command('wsh1', 0, up=True)


def test_netem_commands_on_every_port_and_removal():
    on = netns.netem_commands('wsh1', 2, ['delay', '20ms', 'loss', '1%'])
    assert on == [['ip', 'netns', 'exec', 'wsh1-sw', 'tc', 'qdisc', 'replace', 'dev', 'p%d' % i,
                   'root', 'netem', 'delay', '20ms', 'loss', '1%'] for i in (1, 2)]
    off = netns.netem_commands('wsh1', 2, [])
    assert [argv[6] for argv in off] == ['del', 'del']


def test_ours_matches_only_the_prefix():
    names = ['wsh-sw', 'wsh-h1', 'wsh-h12', 'wsh1-sw', 'wsh1-h1', 'wshx', 'other', 'wsh-hx']
    assert netns.ours('wsh', names) == ['wsh-sw', 'wsh-h1', 'wsh-h12']
    assert netns.ours('wsh1', names) == ['wsh1-sw', 'wsh1-h1']


def test_stale_prefixes_are_dead_test_runs_only():
    names = ['wsh-sw', 'wsh10-sw', 'wsh10-h1', 'wsh20-h1', 'wshprobe5-sw']
    assert netns.stale_prefixes(names, alive=lambda pid: pid == 20) == ['wsh10']


@pytest.mark.parametrize(('text', 'names'), [
    ('', []),
    ('a\nb (id: 3)\n', ['a', 'b']),
    ('\n  \nwsh-h1 (id: 0)', ['wsh-h1']),
])
def test_parse_netns_list(text, names):
    assert netns.parse_netns_list(text) == names
