"""course_desktop.gateway: the one door, on a free port, in front of a stand-in VNC server."""
import base64
import http.client
import os
import socket
import struct
import threading

import pytest
from course_desktop.access import AccessPolicy
from course_desktop.gateway import Gateway

TOKEN = 'gateway-test-token'
GREETING = b'RFB 003.008\n'  # what a VNC server says first


class EchoVnc:
    """A unix-socket server that greets each client, then echoes what it receives."""

    def __init__(self, path):
        self.path = path
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.bind(path)
        self.sock.listen()
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            threading.Thread(target=self._echo, args=(conn,), daemon=True).start()

    @staticmethod
    def _echo(conn):
        with conn:
            conn.sendall(GREETING)
            while True:
                data = conn.recv(65536)
                if not data:
                    return
                conn.sendall(data)

    def close(self):
        self.sock.close()


@pytest.fixture
def novnc_dir(tmp_path):
    folder = tmp_path / 'novnc'
    (folder / 'app').mkdir(parents=True)
    (folder / 'vnc.html').write_text('<html>noVNC</html>')
    (folder / 'app' / 'ui.js').write_text('// ui')
    return str(folder)


def serve(tmp_path, novnc_dir, token=None, vnc=True):
    vnc_socket = str(tmp_path / 'vnc.sock')
    echo = EchoVnc(vnc_socket) if vnc else None
    gateway = Gateway('127.0.0.1', 0, AccessPolicy(0, token), vnc_socket, novnc_dir=novnc_dir)
    port = gateway.server_address[1]
    # The policy names its port in its cookie: give it the one the kernel chose.
    gateway.policy = AccessPolicy(port, token)
    gateway.serve_in_thread(poll_s=0.02)
    return gateway, port, echo


@pytest.fixture
def loopback(tmp_path, novnc_dir):
    gateway, port, echo = serve(tmp_path, novnc_dir)
    yield port
    gateway.shutdown_now()
    echo.close()


@pytest.fixture
def with_token(tmp_path, novnc_dir):
    gateway, port, echo = serve(tmp_path, novnc_dir, TOKEN)
    yield port
    gateway.shutdown_now()
    echo.close()


def get(port, path, headers=None, method='GET'):
    conn = http.client.HTTPConnection('127.0.0.1', port, timeout=10)
    try:
        conn.request(method, path, headers=dict({'Host': '127.0.0.1:%d' % port}, **(headers or {})))
        response = conn.getresponse()
        return response.status, dict(response.getheaders()), response.read()
    finally:
        conn.close()


def test_the_start_page_sends_the_browser_to_novnc(loopback):
    status, headers, _ = get(loopback, '/')
    assert status == 302
    assert headers['Location'].startswith('/vnc.html?autoconnect=1')
    assert 'Set-Cookie' not in headers


def test_novnc_files_are_served_with_headers_that_keep_them_out_of_other_sites(loopback):
    status, headers, body = get(loopback, '/vnc.html')
    assert status == 200 and body == b'<html>noVNC</html>'
    assert headers['X-Frame-Options'] == 'DENY'
    assert "frame-ancestors 'none'" in headers['Content-Security-Policy']
    assert headers['Referrer-Policy'] == 'no-referrer'


def test_no_directory_listing(loopback):
    assert get(loopback, '/app/')[0] == 404


def test_a_foreign_host_name_gets_a_page_saying_why(loopback):
    status, _, body = get(loopback, '/', {'Host': 'rebound.example:%d' % loopback})
    assert status == 403
    assert b'loopback address' in body and b'noVNC' not in body


def test_the_token_becomes_a_cookie_that_opens_the_pages(with_token):
    status, headers, _ = get(with_token, '/?token=' + TOKEN)
    assert status == 302
    cookie = headers['Set-Cookie'].split(';')[0]
    assert cookie == 'course_desktop_%d=%s' % (with_token, TOKEN)
    assert get(with_token, '/vnc.html', {'Cookie': cookie})[0] == 200


@pytest.mark.parametrize('path, headers, text', [
    ('/vnc.html', {}, b'needs its token'),
    ('/app/ui.js', {}, b'needs its token'),
    ('/?token=nope-nope-nope', {}, b'wrong token'),
    ('/vnc.html', {'Cookie': 'course_desktop_1=%s' % TOKEN}, b'needs its token'),
])
def test_without_the_token_no_file_of_the_desktop_is_served(with_token, path, headers, text):
    status, _, body = get(with_token, path, headers)
    assert status == 403 and text in body


def test_head_is_judged_too(with_token):
    assert get(with_token, '/vnc.html', method='HEAD')[0] == 403


# --- the WebSocket ------------------------------------------------------------------------

def open_websocket(port, origin=None, cookie=None, path='/websockify'):
    """A raw WebSocket handshake; returns (socket, status line, response headers)."""
    sock = socket.create_connection(('127.0.0.1', port), timeout=10)
    key = base64.b64encode(os.urandom(16)).decode()
    lines = ['GET %s HTTP/1.1' % path, 'Host: 127.0.0.1:%d' % port, 'Upgrade: websocket',
             'Connection: Upgrade', 'Sec-WebSocket-Key: %s' % key, 'Sec-WebSocket-Version: 13',
             'Sec-WebSocket-Protocol: binary']
    if origin:
        lines.append('Origin: %s' % origin)
    if cookie:
        lines.append('Cookie: %s' % cookie)
    sock.sendall(('\r\n'.join(lines) + '\r\n\r\n').encode())
    head = b''
    while b'\r\n\r\n' not in head:
        chunk = sock.recv(1)
        if not chunk:
            break
        head += chunk
    status, *header_lines = head.decode().split('\r\n')
    headers = dict(line.split(': ', 1) for line in header_lines if ': ' in line)
    return sock, status, headers


def send_frame(sock, payload):
    """One masked binary frame, as a browser sends it."""
    mask = os.urandom(4)
    masked = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
    assert len(payload) < 126
    sock.sendall(bytes([0x82, 0x80 | len(payload)]) + mask + masked)


def read_frame(sock):
    """(opcode, payload) of one unmasked frame from the server."""
    def exactly(n):
        data = b''
        while len(data) < n:
            chunk = sock.recv(n - len(data))
            assert chunk, 'the gateway closed the connection'
            data += chunk
        return data
    first, second = exactly(2)
    length = second & 0x7F
    if length == 126:
        length = struct.unpack('>H', exactly(2))[0]
    elif length == 127:
        length = struct.unpack('>Q', exactly(8))[0]
    return first & 0x0F, exactly(length)


def test_the_websocket_relays_both_ways_to_the_vnc_server(loopback):
    origin = 'http://127.0.0.1:%d' % loopback
    sock, status, headers = open_websocket(loopback, origin)
    with sock:
        assert status.startswith('HTTP/1.1 101')
        assert headers.get('Sec-WebSocket-Protocol') == 'binary'
        assert read_frame(sock) == (0x2, GREETING)
        send_frame(sock, b'key press')
        assert read_frame(sock) == (0x2, b'key press')


def test_the_websocket_with_the_token_cookie(with_token):
    cookie = 'course_desktop_%d=%s' % (with_token, TOKEN)
    sock, status, _ = open_websocket(with_token, 'http://127.0.0.1:%d' % with_token, cookie)
    with sock:
        assert status.startswith('HTTP/1.1 101')
        assert read_frame(sock) == (0x2, GREETING)


@pytest.mark.parametrize('origin', [None, 'http://evil.example'])
def test_a_websocket_from_another_page_is_refused(loopback, origin):
    sock, status, _ = open_websocket(loopback, origin)
    sock.close()
    assert status.startswith('HTTP/1.1 403')


def test_a_websocket_without_the_token_is_refused(with_token):
    sock, status, _ = open_websocket(with_token, 'http://127.0.0.1:%d' % with_token)
    sock.close()
    assert status.startswith('HTTP/1.1 403')


def test_a_websocket_elsewhere_than_novncs_path_is_not_found(loopback):
    sock, status, _ = open_websocket(loopback, 'http://127.0.0.1:%d' % loopback, path='/other')
    sock.close()
    assert status.startswith('HTTP/1.1 404')


def test_no_vnc_server_closes_the_websocket_with_a_reason(tmp_path, novnc_dir):
    gateway, port, _ = serve(tmp_path, novnc_dir, vnc=False)
    try:
        sock, status, _ = open_websocket(port, 'http://127.0.0.1:%d' % port)
        with sock:
            assert status.startswith('HTTP/1.1 101')
            opcode, payload = read_frame(sock)
            assert opcode == 0x8  # close
            assert struct.unpack('>H', payload[:2])[0] == 1011
            assert b'VNC server is not running' in payload
    finally:
        gateway.shutdown_now()


def test_the_port_in_use_is_an_oserror_at_construction(tmp_path, novnc_dir):
    gateway, port, echo = serve(tmp_path, novnc_dir)
    try:
        with pytest.raises(OSError):
            Gateway('127.0.0.1', port, AccessPolicy(port), str(tmp_path / 'x.sock'),
                    novnc_dir=novnc_dir)
    finally:
        gateway.shutdown_now()
        echo.close()
