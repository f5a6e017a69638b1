"""The desktop's one network door: noVNC's page and a WebSocket to the VNC server, behind the
access policy (course_desktop.access).

One threaded HTTP server serves Debian's noVNC files and, on /websockify, relays the browser's
WebSocket (websockify's RFC 6455 implementation) to the VNC server's unix socket: the VNC and
X servers have no TCP port at all, so this door, with its token and its Host and Origin
checks, is the only way in.
"""
import functools
import html
import http.server
import select
import socket
import sys
import threading

from course_desktop.access import WEBSOCKET_PATH, novnc_location
from websockify.websocket import WebSocketWantReadError, WebSocketWantWriteError
from websockify.websocketserver import WebSocketRequestHandlerMixIn

NOVNC_DIR = '/usr/share/novnc'  # Debian's novnc package
RELAY_CHUNK = 65536  # bytes read from the VNC server at a time: a screen update's worth
#: A browser page a refused visitor sees: what is wrong, what to do, and no desktop.
REFUSED_PAGE = '''<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>Course desktop: %(title)s</title></head>
<body style="font-family: sans-serif; max-width: 40em; margin: 3em auto">
<h1>%(title)s</h1><p>%(reason)s</p></body></html>
'''


class BinaryWebSocket(WebSocketRequestHandlerMixIn.SocketClass):
    """noVNC's WebSocket: binary frames; answers the 'binary' sub-protocol if it is offered
    (older noVNC pages ask for it; websockify's own server answers it the same way).

    Built on the mix-in's own socket class: websockify 0.10 (Debian 12) makes a plain
    WebSocket(), 0.12 (Debian 13) an HttpWebSocket(handler) that answers through the handler.
    """

    def select_subprotocol(self, protocols):
        offered = [p.strip() for p in protocols]
        return 'binary' if 'binary' in offered else ''


class GatewayHandler(WebSocketRequestHandlerMixIn, http.server.SimpleHTTPRequestHandler):
    """One HTTP request, or one WebSocket for its whole life."""

    SocketClass = BinaryWebSocket
    server_version = 'course-desktop'
    sys_version = ''
    protocol_version = 'HTTP/1.1'

    def parse_request(self):
        # Every method and path passes the policy first: a refused request gets a page that
        # says why, and never noVNC's files or the WebSocket.
        if not super().parse_request():
            return False
        self.verdict = self.server.policy.judge(self.path, self.headers)
        if not self.verdict.allowed:
            self.refuse(self.verdict.status, self.verdict.reason)
            return False
        return True

    def refuse(self, status, reason):
        body = (REFUSED_PAGE % {'title': 'access refused',
                                'reason': html.escape(reason)}).encode()
        self.send_response(status)
        self.send_header('Content-Type', 'text/html; charset=utf-8')
        self.send_header('Content-Length', str(len(body)))
        self.send_header('Connection', 'close')
        self.end_headers()
        if self.command != 'HEAD':
            self.wfile.write(body)
        self.close_connection = True

    def end_headers(self):
        verdict = getattr(self, 'verdict', None)
        if verdict is not None and verdict.set_cookie:
            self.send_header('Set-Cookie', verdict.set_cookie)
        # The desktop is a terminal on the student's machine: never inside another site's
        # frame, and no token leaks in a Referer.
        self.send_header('Content-Security-Policy', "frame-ancestors 'none'")
        self.send_header('X-Frame-Options', 'DENY')
        self.send_header('Referrer-Policy', 'no-referrer')
        super().end_headers()

    def do_GET(self):
        if self._is_start_page():
            self._send_to_novnc()
        else:
            super().do_GET()

    def do_HEAD(self):
        if self._is_start_page():
            self._send_to_novnc()
        else:
            super().do_HEAD()

    def _is_start_page(self):
        return self.path.split('?', 1)[0] in ('/', '/index.html')

    def _send_to_novnc(self):
        self.send_response(302)
        self.send_header('Location', novnc_location())
        self.send_header('Content-Length', '0')
        self.end_headers()

    def list_directory(self, path):
        self.send_error(404, 'No such file')

    def handle_upgrade(self):
        if self.path.split('?', 1)[0] != WEBSOCKET_PATH:
            self.send_error(404, 'No WebSocket here (noVNC connects to %s)' % WEBSOCKET_PATH)
            return
        super().handle_upgrade()

    def handle_websocket(self):
        try:
            target = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            target.connect(self.server.vnc_socket)
        except OSError as err:
            sys.stderr.write('desktop: cannot reach the VNC server at %s: %s\n'
                             % (self.server.vnc_socket, err))
            self.request.close(1011, 'the desktop\'s VNC server is not running')
            return
        try:
            relay(self.request, target)
        finally:
            target.close()

    def log_message(self, fmt, *args):
        if self.server.verbose:
            super().log_message(fmt, *args)

    def log_error(self, fmt, *args):
        # http.server's own errors are a browser's requests answered 404 (noVNC asks for a
        # package.json Debian leaves out) or a page closed mid-request: --verbose shows them.
        if self.server.verbose:
            super().log_error(fmt, *args)


def relay(ws, target):
    """Copies VNC bytes both ways between a browser's WebSocket and the VNC server until
    either side closes. One thread: select says who has something to say."""
    try:
        while True:
            if not ws.pending():
                readable, _, _ = select.select([ws, target], [], [])
            else:
                readable = [ws]
            if ws in readable:
                try:
                    message = ws.recvmsg()
                except WebSocketWantReadError:
                    message = b''  # part of a frame: the rest comes with the next read
                if message is None:
                    return  # the browser closed the page
                if message:
                    target.sendall(message)
            if target in readable:
                data = target.recv(RELAY_CHUNK)
                if not data:
                    ws.close(1000, 'the VNC server closed the session')
                    return
                _send_whole(ws, data)
    except (OSError, WebSocketWantWriteError):
        return  # either side went away mid-message: nothing left to relay to


def _send_whole(ws, data):
    """sendmsg on a blocking socket, repeated (with the same data, as it asks) until the
    whole frame is out."""
    while True:
        try:
            ws.sendmsg(data)
            return
        except WebSocketWantWriteError:
            continue


class Gateway(http.server.ThreadingHTTPServer):
    """The HTTP server: bound at construction (OSError if the address cannot be had)."""

    daemon_threads = True  # a browser tab left open must not keep the desktop from stopping

    def __init__(self, address, port, policy, vnc_socket, novnc_dir=NOVNC_DIR, verbose=False):
        if ':' in address:
            self.address_family = socket.AF_INET6
        self.policy = policy
        self.vnc_socket = vnc_socket
        self.verbose = verbose
        self._thread = None
        handler = functools.partial(GatewayHandler, directory=novnc_dir)
        super().__init__((address, port), handler)

    def serve_in_thread(self, poll_s=0.5):
        """Serves in a thread of its own; shutdown_now() takes up to poll_s to stop it."""
        self._thread = threading.Thread(target=self.serve_forever, args=(poll_s,),
                                        name='desktop gateway', daemon=True)
        self._thread.start()

    def shutdown_now(self):
        """Stops serving (if it started) and closes the listening socket."""
        if self._thread is not None:
            self.shutdown()
            self._thread = None
        self.server_close()
