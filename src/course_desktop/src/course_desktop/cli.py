"""`./ws desktop`: the course's desktop in a web browser, in the foreground until Ctrl-C.

Order of start-up: the checks that need nothing running (programs, the workspace folder), the
network door (a taken port fails here, before anything starts), the X session, then a visit
to its own page; only then the one URL to open is printed. Any failure: one line saying what
and what to do, everything started is stopped, exit 1.
"""
import errno
import http.client
import os
import pwd
import shutil
import signal
import socket
import sys
import tempfile
import threading
import urllib.parse

from course_desktop.access import AccessPolicy, start_path, url_host
from course_desktop.gateway import NOVNC_DIR, Gateway
from course_desktop.options import parse_options
from course_desktop.x_session import SessionError, XSession

from course_desktop import reaper

#: The programs the desktop runs, and the Debian package of each (tools/debian-packages.txt).
PROGRAMS = {'Xvnc': 'tigervnc-standalone-server', 'openbox': 'openbox', 'xterm': 'xterm',
            'xauth': 'xauth', 'xdotool': 'xdotool'}
RCFILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'terminal.bashrc')
SELF_CHECK_TIMEOUT_S = 10.0
WATCH_S = 1.0  # how often the idle desktop looks at its X server and reaps orphans
CONTAINER_MARKERS = ('/.dockerenv', '/run/.containerenv')  # Docker's, Podman's


class DesktopError(RuntimeError):
    """Why the desktop cannot run, said for the user: printed alone, exit 1."""


def main(argv=None):
    options = parse_options(sys.argv[1:] if argv is None else argv)
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, lambda *_: stop.set())
    desktop = Desktop(options)
    try:
        desktop.start()
        for line in desktop.banner():
            print(line, flush=True)
        code = desktop.run_until(stop)
    except DesktopError as err:
        print('desktop: %s' % err, file=sys.stderr, flush=True)
        code = 1
    finally:
        desktop.stop()
    sys.exit(code)


class Desktop:
    """One desktop: its door (the gateway), its X session, its session folder; start() raises
    DesktopError, stop() undoes whatever start() did, whenever it stopped."""

    def __init__(self, options):
        self.options = options
        self.policy = AccessPolicy(options.port, options.token)
        self.gateway = self.session = self.runtime_dir = None

    def start(self):
        check_programs()
        prepare_workspace(self.options.workspace)
        reaper.become_subreaper()
        self.runtime_dir = tempfile.mkdtemp(prefix='course-desktop-')  # mode 0700
        env = dict(os.environ, COURSE_WS_SETUP=self.options.course_setup,
                   COURSE_DESKTOP_WORKSPACE=self.options.workspace)
        env.pop('WAYLAND_DISPLAY', None)
        self.session = XSession(self.runtime_dir, self.options.geometry, RCFILE, env)
        self.gateway = bind_gateway(self.options, self.policy, self.session.vnc_socket)
        try:
            self.session.start()
        except SessionError as err:
            raise DesktopError(str(err)) from None
        self.gateway.serve_in_thread()
        self_check(self.local_url())

    def local_url(self):
        """The page as this machine reaches it (the self-check's address)."""
        address = self.options.listen
        if address in ('0.0.0.0', ''):
            address = '127.0.0.1'
        elif address == '::':
            address = '::1'
        return 'http://%s:%d%s' % (url_host(address), self.options.port,
                                   start_path(self.options.token))

    def urls(self):
        """The URLs to print: the one to open first."""
        port, path, listen = self.options.port, start_path(self.options.token), self.options.listen
        if listen in ('0.0.0.0', '::', ''):
            if any(os.path.exists(m) for m in CONTAINER_MARKERS):
                # Inside a container, the port is whatever `docker run -p` published: the
                # README's command publishes it on the host's loopback, same number.
                return ['http://localhost:%d%s' % (port, path)]
            # This machine's own address first: its name may not resolve (a fresh VM, a
            # renamed machine); the name is for the other machines.
            return ['http://127.0.0.1:%d%s' % (port, path),
                    'http://%s:%d%s' % (socket.gethostname(), port, path)]
        return ['http://%s:%d%s' % (url_host(listen), port, path)]

    def banner(self):
        urls = self.urls()
        lines = ['desktop: open %s' % urls[0]]
        lines += ['desktop:   from another machine: %s' % url for url in urls[1:]]
        lines += ['desktop: your workspace: %s (overlaid on the course workspace)'
                  % self.options.workspace,
                  'desktop: X programs from elsewhere: DISPLAY=%s XAUTHORITY=%s'
                  % (self.session.display, self.session.xauthority),
                  'desktop: serving on %s:%d%s; Ctrl-C stops it and everything it started'
                  % (url_host(self.options.listen), self.options.port,
                     '' if self.options.token is None else ', token required')]
        return lines

    def run_until(self, stop):
        """Waits for a stop signal; exit code 1 if the X server died first."""
        while not stop.wait(WATCH_S):
            reaper.reap_orphans(self._known_children())
            if not self.session.alive():
                print('desktop: the X server (Xvnc) ended; its log: %s'
                      % self.session.xvnc.tail(), file=sys.stderr, flush=True)
                return 1
        return 0

    def _known_children(self):
        session = self.session
        return {child.pid for child in (session.xvnc, session.window_manager,
                                        session.terminal) if child is not None}

    def stop(self):
        if self.gateway is not None:
            self.gateway.shutdown_now()
        known = self._known_children() if self.session is not None else set()
        reaper.stop_tree(known)
        if self.session is not None:
            for child in (self.session.terminal, self.session.window_manager, self.session.xvnc):
                if child is not None:
                    child.stop(timeout_s=1.0)
        if self.runtime_dir is not None:
            shutil.rmtree(self.runtime_dir, ignore_errors=True)


def check_programs():
    missing = [name for name in PROGRAMS if shutil.which(name) is None]
    if not os.path.isfile(os.path.join(NOVNC_DIR, 'vnc.html')):
        missing.append('noVNC (%s)' % NOVNC_DIR)
    if missing:
        packages = sorted({PROGRAMS.get(name, 'novnc') for name in missing})
        raise DesktopError('missing %s: install the Debian packages %s (./ws deps does)'
                           % (', '.join(missing), ' '.join(packages)))


def prepare_workspace(workspace):
    """The student's workspace exists with a src/ and is writable, or DesktopError."""
    try:
        os.makedirs(os.path.join(workspace, 'src'), exist_ok=True)
    except OSError as err:
        raise DesktopError('cannot create your workspace %s: %s' % (workspace, err.strerror)) \
            from None
    if not os.access(workspace, os.W_OK | os.X_OK):
        raise DesktopError('your workspace %s is not writable by %s (uid %d): give it to '
                           'that user, or choose another with --workspace'
                           % (workspace, _user(), os.getuid()))


def bind_gateway(options, policy, vnc_socket):
    try:
        return Gateway(options.listen, options.port, policy, vnc_socket,
                       verbose=options.verbose)
    except OSError as err:
        raise DesktopError(bind_error_message(err, options.listen, options.port)) from None


def bind_error_message(err, listen, port):
    """What a failed bind of the desktop's address means for the user, and what to do."""
    if isinstance(err, socket.gaierror):
        return '--listen %r is not an address this machine can serve on: %s' % (listen,
                                                                                 err.strerror)
    if err.errno == errno.EADDRINUSE:
        return ('port %d is taken on %s (another desktop, or another program): stop it, or '
                'choose another port with --port' % (port, listen))
    if err.errno == errno.EADDRNOTAVAIL:
        return ('%s is not an address of this machine: --listen takes one of its own '
                'addresses, or 0.0.0.0 for all' % listen)
    if err.errno == errno.EACCES:
        return ('no permission to serve on port %d (ports below 1024 need root): choose a port '
                'above 1023' % port)
    return 'cannot serve on %s:%d: %s' % (url_host(listen), port, err.strerror or err)


def self_check(url):
    """Visits the page as a browser on this machine would (the answer: on to noVNC's page),
    or DesktopError."""
    parts = urllib.parse.urlsplit(url)
    connection = http.client.HTTPConnection(parts.hostname, parts.port,
                                            timeout=SELF_CHECK_TIMEOUT_S)
    try:
        connection.request('GET', '%s?%s' % (parts.path, parts.query) if parts.query
                           else parts.path)
        status = connection.getresponse().status
    except OSError as err:
        raise DesktopError('the desktop\'s page at %s cannot be reached from this machine: %s'
                           % (url, err)) from None
    finally:
        connection.close()
    if status != 302:
        raise DesktopError('the desktop\'s page at %s answered HTTP %d, not the way on to '
                           'noVNC' % (url, status))


def _user():
    try:
        return pwd.getpwuid(os.getuid()).pw_name
    except KeyError:
        return 'this user'
