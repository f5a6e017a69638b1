"""The desktop's command line (`./ws desktop [OPTIONS]`), read into one frozen record (pure).

Bad values are refused here, each with what was given and what is expected, before anything
starts; argparse exits 2 on them, as every command-line tool does.
"""
import argparse
import os
import re
from dataclasses import dataclass

from course_desktop.access import AccessError, check_token, is_loopback, new_token

DEFAULT_LISTEN = '127.0.0.1'
DEFAULT_PORT = 6080  # noVNC's customary port
DEFAULT_GEOMETRY = '1280x800'  # until the browser tab sizes it (noVNC's resize=remote)
TOKEN_ENV = 'COURSE_DESKTOP_TOKEN'  # a token given by the environment (docker run -e ...)
GEOMETRY = re.compile(r'^(\d{3,4})x(\d{3,4})$')
MIN_SIDE, MAX_SIDE = 640, 4096  # pixels: room for Stage's window; TigerVNC's own limit is larger


@dataclass(frozen=True)
class DesktopOptions:
    listen: str
    port: int
    token: str  # None: loopback without a token
    workspace: str
    course_setup: str
    geometry: str
    verbose: bool


def parser():
    p = argparse.ArgumentParser(
        prog='ws desktop',
        description='A desktop in your web browser with the course workspace: its terminal, '
                    'and the windows of Stage, turtlesim, rviz and rqt_graph. It runs until '
                    'Ctrl-C (or SIGTERM) and then stops everything it started.')
    p.add_argument('--listen', default=DEFAULT_LISTEN, metavar='ADDR',
                   help='the address to serve on (default %(default)s: this machine only; any '
                        'other address requires the token)')
    p.add_argument('--port', type=int, default=DEFAULT_PORT,
                   help='the port (default %(default)s)')
    p.add_argument('--token', default=None,
                   help='the token the page asks for (default: $%s, else a new random one when '
                        'listening beyond loopback, none on loopback)' % TOKEN_ENV)
    p.add_argument('--workspace', default=os.path.expanduser('~/catkin_ws'), metavar='DIR',
                   help='your own catkin workspace, overlaid on the course\'s '
                        '(default %(default)s; created if missing)')
    p.add_argument('--course-setup', default=os.environ.get('COURSE_WS_SETUP'), metavar='FILE',
                   help='the course workspace\'s devel/setup.bash (./ws passes it)')
    p.add_argument('--geometry', default=DEFAULT_GEOMETRY, metavar='WxH',
                   help='the screen before the browser resizes it (default %(default)s)')
    p.add_argument('--verbose', action='store_true', help='log every HTTP request')
    return p


def parse_options(argv, environ=None):
    """DesktopOptions from argv (after the program name); argparse's exit 2 on bad values."""
    environ = os.environ if environ is None else environ
    p = parser()
    args = p.parse_args(argv)
    if not 1 <= args.port <= 65535:
        p.error('--port must be 1..65535, got %d' % args.port)
    match = GEOMETRY.match(args.geometry)
    if not match or not all(MIN_SIDE <= int(side) <= MAX_SIDE for side in match.groups()):
        p.error('--geometry must be WIDTHxHEIGHT, each %d..%d pixels, got %r'
                % (MIN_SIDE, MAX_SIDE, args.geometry))
    if not args.course_setup:
        p.error('--course-setup is missing (./ws desktop passes the workspace\'s setup.bash)')
    token = args.token if args.token is not None else environ.get(TOKEN_ENV) or None
    try:
        if token is not None:
            check_token(token)
        elif not is_loopback(args.listen):
            token = new_token()
    except AccessError as err:
        p.error('--token: %s' % err)
    return DesktopOptions(listen=args.listen, port=args.port, token=token,
                          workspace=os.path.abspath(os.path.expanduser(args.workspace)),
                          course_setup=args.course_setup, geometry=args.geometry,
                          verbose=args.verbose)
