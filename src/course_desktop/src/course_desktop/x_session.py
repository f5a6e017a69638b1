"""The desktop's X session: TigerVNC's Xvnc, the openbox window manager and the workspace's
terminal, on a display of their own.

Xvnc picks a free display itself (-displayfd) and serves VNC on a unix socket only (mode 0600,
in a folder only this user can enter): no VNC or X port exists on any network address. X
clients need the session's cookie (XAUTHORITY), so another user of a shared machine cannot
open windows on, or read keys from, this desktop either.
"""
import os
import secrets
import shlex
import subprocess

from course_common.processes import ChildProcess
from course_common.waiting import WaitError, wait_for
from course_common.xvfb import display_number
from course_desktop.openbox import openbox_config, openbox_menu

START_TIMEOUT_S = 30.0  # Xvnc and openbox start in well under a second; a loaded machine is slower
TERMINAL_TITLE = 'Terminal: course workspace'
TERMINAL_FONT = ('DejaVu Sans Mono', 11)  # fonts-dejavu-core; readable in a browser tab
TERMINAL_SIZE = '80x24'  # columns x rows: the classic terminal, leaving room for Stage's window
FIRST_TERMINAL_AT = '+16+16'  # the next ones go where openbox finds room, not on top of it


class SessionError(RuntimeError):
    """A part of the X session did not start; the message says which and what it printed."""


def terminal_argv(rcfile, position=''):
    """xterm running an interactive bash that reads the desktop's rc file (the workspace,
    then the student's overlay); at `position` ('+X+Y'), or where openbox finds room."""
    return ['xterm', '-title', TERMINAL_TITLE, '-fa', TERMINAL_FONT[0],
            '-fs', str(TERMINAL_FONT[1]), '-geometry', TERMINAL_SIZE + position,
            '-xrm', 'XTerm*selectToClipboard: true', '-e', 'bash', '--rcfile', rcfile, '-i']


def xvnc_argv(geometry, vnc_socket, xauthority):
    """Xvnc serving VNC on vnc_socket only, no TCP at all, X clients by cookie."""
    return ['Xvnc', '-displayfd', '1', '-geometry', geometry, '-depth', '24',
            '-rfbunixpath', vnc_socket, '-rfbunixmode', '0600', '-rfbport', '-1',
            # The socket is the lock: only this user reaches it, and the gateway in front of
            # it checks the browser. Several browser tabs may share the one desktop.
            '-SecurityTypes', 'None', '-AlwaysShared', '-AcceptSetDesktopSize',
            '-nolisten', 'tcp', '-auth', xauthority, '-desktop', 'Course desktop']


class XSession:
    """Xvnc, openbox and the first terminal, their files (cookie, VNC socket, configuration,
    logs) in runtime_dir; started by start(), stopped with everything else the desktop
    started (course_desktop.reaper)."""

    def __init__(self, runtime_dir, geometry, rcfile, env):
        self.runtime_dir = runtime_dir
        self.geometry = geometry
        self.rcfile = rcfile
        self.vnc_socket = os.path.join(runtime_dir, 'vnc.sock')
        self.xauthority = os.path.join(runtime_dir, 'Xauthority')
        self.display = None
        self._env = dict(env)
        self._cookie = secrets.token_hex(16)
        self.xvnc = self.window_manager = self.terminal = None

    def env(self):
        """The environment of every program on this desktop."""
        return dict(self._env, DISPLAY=self.display, XAUTHORITY=self.xauthority)

    def start(self):
        # The server reads every cookie of its -auth file at start, whatever display it names;
        # clients look theirs up by display, added once the display is known.
        self._xauth('add', ':0', '.', self._cookie)
        self.xvnc = self._child('Xvnc', xvnc_argv(self.geometry, self.vnc_socket,
                                                  self.xauthority), env=self._env)
        try:
            number = wait_for(lambda: display_number(self.xvnc.lines()), START_TIMEOUT_S,
                              'Xvnc to report its display', alive=self.xvnc.alive)
        except WaitError as err:
            raise SessionError('Xvnc did not start (%s); it said:\n%s'
                               % (err, self.xvnc.tail())) from None
        self.display = ':' + number
        self._xauth('add', self.display, '.', self._cookie)
        self._write_openbox_files()
        self.window_manager = self._child('openbox', [
            'openbox', '--config-file', os.path.join(self.runtime_dir, 'openbox-rc.xml')])
        self._wait_window_manager()
        self.open_terminal()
        self._focus_terminal()
        return self

    def open_terminal(self):
        """The first workspace terminal, in the top left corner (Ctrl+Alt+T and the desktop's
        menu open more, through openbox)."""
        self.terminal = self._child('xterm', terminal_argv(self.rcfile, FIRST_TERMINAL_AT),
                                    cwd=self._env.get('COURSE_DESKTOP_WORKSPACE'))
        return self.terminal

    def _focus_terminal(self):
        """Waits for the first terminal's window and gives it the keyboard: what the student
        types in the page goes to it (noVNC sends keys to whichever window has the focus)."""
        def focused():
            found = self._xdotool('search', '--onlyvisible', '--name', '^%s$' % TERMINAL_TITLE)
            window = found.split()[0] if found else None
            if window is None:
                return None
            self._xdotool('windowactivate', window)
            return self._xdotool('getactivewindow') == window
        try:
            wait_for(focused, START_TIMEOUT_S, "the terminal's window to take the keyboard",
                     alive=self.terminal.alive)
        except WaitError as err:
            raise SessionError('%s; xterm said:\n%s' % (err, self.terminal.tail())) from None

    def _wait_window_manager(self):
        """Waits until openbox manages the screen (it then answers EWMH's desktop count): a
        window mapped before that would not be given the focus."""
        try:
            wait_for(lambda: self._xdotool('get_num_desktops'), START_TIMEOUT_S,
                     'openbox to manage the screen', alive=self.window_manager.alive)
        except WaitError as err:
            raise SessionError('%s; openbox said:\n%s' % (err, self.window_manager.tail())) \
                from None

    def _xdotool(self, *args):
        """xdotool's output, stripped ('' when it fails: nothing found yet, no manager yet)."""
        try:
            done = subprocess.run(('xdotool',) + args, env=self.env(), timeout=10,
                                  stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        except (OSError, subprocess.SubprocessError):
            return ''
        return done.stdout.strip() if done.returncode == 0 else ''

    def _write_openbox_files(self):
        command = ' '.join(shlex.quote(a) for a in terminal_argv(self.rcfile))
        menu = os.path.join(self.runtime_dir, 'openbox-menu.xml')
        with open(menu, 'w', encoding='utf-8') as f:
            f.write(openbox_menu(command))
        with open(os.path.join(self.runtime_dir, 'openbox-rc.xml'), 'w', encoding='utf-8') as f:
            f.write(openbox_config(command, menu))

    def _child(self, name, argv, env=None, cwd=None):
        child = ChildProcess(argv, env=env or self.env(), cwd=cwd,
                             log_path=os.path.join(self.runtime_dir, name + '.log'))
        try:
            return child.start()
        except OSError as err:
            raise SessionError('cannot start %s: %s' % (argv[0], err)) from None

    def _xauth(self, *args):
        try:
            subprocess.run(['xauth', '-q', '-f', self.xauthority] + list(args), check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=30)
        except (OSError, subprocess.SubprocessError) as err:
            raise SessionError('xauth could not write the session\'s cookie: %s' % err) from None

    def alive(self):
        """True while the X server runs."""
        return self.xvnc is not None and self.xvnc.alive()
