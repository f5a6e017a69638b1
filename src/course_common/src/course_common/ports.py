"""free_port: a TCP port for a private master (convoy_demo, the benchmarks, the tests)."""
import socket


def free_port(host='localhost'):
    """A TCP port that is free on `host` right now (the kernel picks it; another process
    may take it before it is used, which a private master then reports at start-up)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind((host, 0))
        return sock.getsockname()[1]
