"""free_port: a TCP port for a private master (convoy_demo, the benchmarks, the tests)."""
import random
import socket

EPHEMERAL_RANGE = '/proc/sys/net/ipv4/ip_local_port_range'
LOWEST_PORT = 10000     # above the ports services commonly listen on
MASTER_PORT = 11311     # ROS's default master: a student's roscore may want it
TRIES = 200


def free_port(host='localhost'):
    """A TCP port free on `host` right now, below the kernel's ephemeral range.

    Outgoing connections take their local ports from that range (a swarm test opens
    thousands), so a port picked there can be taken before the master binds it; a port below
    it is only ever taken by another bind. Another process may still bind it first, which a
    private master then reports at start-up."""
    low = _ephemeral_low()
    for _ in range(TRIES):
        port = random.randrange(LOWEST_PORT, low)
        if port != MASTER_PORT and _bindable(host, port):
            return port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:  # all taken: the kernel's pick
        sock.bind((host, 0))
        return sock.getsockname()[1]


def _ephemeral_low(path=EPHEMERAL_RANGE):
    """The ephemeral range's first port (Linux's default 32768 where it cannot be read)."""
    try:
        with open(path, encoding='ascii') as f:
            low = int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        low = 32768
    return max(low, LOWEST_PORT + 1000)


def _bindable(host, port):
    """True if nothing is bound to `port`, on `host` or on every address (a master binds
    every address)."""
    for address in ('', host):
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
            try:
                sock.bind((address, port))
            except OSError:
                return False
    return True
