"""Who may see the desktop: the token, its cookie, and the Host and Origin checks (pure).

Two modes, as Jupyter has them:
- on a loopback address, no token: only this machine can connect at all;
- on any other address, a token: given once in the URL (`/?token=...`), it becomes a cookie
  (HttpOnly, SameSite=Strict) that every page, file and the VNC WebSocket must then carry.
In both modes the WebSocket must come from a page of this server (its Origin names the Host
it was sent to), and on loopback the Host must be a loopback name: a web page elsewhere that
the student visits can neither open the desktop's WebSocket nor reach it by rebinding a
name of its own to 127.0.0.1.
"""
import hmac
import ipaddress
import re
import secrets
from dataclasses import dataclass
from http.cookies import CookieError, SimpleCookie
from urllib.parse import parse_qs, urlsplit

TOKEN_BYTES = 24  # secrets.token_urlsafe: 32 characters, 192 bits
MIN_TOKEN_CHARS = 8  # a token given by hand: short enough to type, long enough not to guess
TOKEN_CHARS = re.compile(r'^[A-Za-z0-9_.~-]+$')  # a URL query value that needs no escaping
LOOPBACK_NAMES = ('localhost',)
#: noVNC's page with what a student expects: connect at once, the remote screen the size of
#: the browser tab, reconnect after a drop (a restarted container, a laptop waking up).
NOVNC_PAGE = 'vnc.html'
NOVNC_QUERY = 'autoconnect=1&resize=remote&reconnect=1&reconnect_delay=1000'
WEBSOCKET_PATH = '/websockify'  # noVNC's default `path`


class AccessError(ValueError):
    """A token or address given on the command line that cannot be used."""


def new_token():
    """A fresh random token (URL-safe)."""
    return secrets.token_urlsafe(TOKEN_BYTES)


def check_token(token):
    """token, if it can serve as one; AccessError saying what is wrong otherwise."""
    if len(token) < MIN_TOKEN_CHARS:
        raise AccessError('a token needs at least %d characters, got %d'
                          % (MIN_TOKEN_CHARS, len(token)))
    if not TOKEN_CHARS.match(token):
        raise AccessError('a token may hold only letters, digits and - _ . ~ (it goes into a URL)')
    return token


def is_loopback(address):
    """True for a loopback IP address (127.0.0.0/8, ::1) or the name localhost."""
    if address in LOOPBACK_NAMES:
        return True
    try:
        return ipaddress.ip_address(address).is_loopback
    except ValueError:
        return False


def split_host(host_header):
    """(name, port or None) of an HTTP Host header value ('[::1]:6080', 'localhost')."""
    host = host_header.strip().lower()
    if host.startswith('['):
        name, _, rest = host[1:].partition(']')
        port = rest[1:] if rest.startswith(':') else None
    else:
        name, sep, port = host.rpartition(':')
        if not sep:
            name, port = host, None
    return name, port


@dataclass(frozen=True)
class Verdict:
    """What to answer a request: allowed, or refused with an HTTP status and a reason; and,
    when the request brought the right token in its URL, the cookie to set."""
    allowed: bool
    status: int = 200
    reason: str = ''
    set_cookie: str = ''


ALLOWED = Verdict(True)


@dataclass(frozen=True)
class AccessPolicy:
    """The desktop's rule for one server: its port and token (None: loopback, no token)."""
    port: int
    token: str = None

    @property
    def cookie_name(self):
        # Cookies are shared by every port of a host: one name per port keeps two desktops
        # on one machine (two students on a lab server) from overwriting each other's.
        return 'course_desktop_%d' % self.port

    def cookie_header(self):
        """The Set-Cookie value that lets this browser in from now on."""
        return '%s=%s; Path=/; HttpOnly; SameSite=Strict' % (self.cookie_name, self.token)

    def judge(self, path, headers):
        """The verdict on a request for path (with its query) with these headers (a mapping
        with .get, names case-insensitive as http.server's are)."""
        host = headers.get('Host') or ''
        name, _ = split_host(host)
        if self.token is None and not is_loopback(name):
            return Verdict(False, 403, 'this desktop answers only at a loopback address '
                           '(http://127.0.0.1:%d/), not at %r' % (self.port, host))
        if headers.get('Upgrade', '').lower() == 'websocket' and not same_origin(headers):
            return Verdict(False, 403, 'the desktop\'s WebSocket opens only from its own page '
                           '(Origin %r, Host %r)' % (headers.get('Origin'), host))
        if self.token is None:
            return ALLOWED
        if _same(query_token(path), self.token):
            return Verdict(True, set_cookie=self.cookie_header())
        if _same(cookie_value(headers.get('Cookie'), self.cookie_name), self.token):
            return ALLOWED
        if query_token(path) is not None:
            return Verdict(False, 403, 'wrong token: open the URL the desktop printed')
        return Verdict(False, 403, 'this desktop needs its token: open the URL the desktop '
                       'printed when it started (http://...:%d/?token=...)' % self.port)


def same_origin(headers):
    """True when the request's Origin is http(s)://<its Host>: sent by a page of this server."""
    origin, host = headers.get('Origin'), headers.get('Host')
    if not origin or not host:
        return False
    parts = urlsplit(origin)
    return parts.scheme in ('http', 'https') and parts.netloc.lower() == host.strip().lower()


def query_token(path):
    """The token= value in a request path's query, or None."""
    values = parse_qs(urlsplit(path).query).get('token')
    return values[0] if values else None


def cookie_value(cookie_header, name):
    """The value of cookie `name` in a Cookie header, or None (also for a malformed header)."""
    if not cookie_header:
        return None
    jar = SimpleCookie()
    try:
        jar.load(cookie_header)
    except CookieError:
        return None
    morsel = jar.get(name)
    return morsel.value if morsel is not None else None


def _same(given, token):
    """Compares in constant time, so the answer's timing tells nothing of the token."""
    return given is not None and hmac.compare_digest(given.encode(), token.encode())


def start_path(token=None):
    """The path the printed URL opens: the token (if any) goes in, the server answers with
    its cookie and sends the browser on to noVNC's page."""
    return '/?token=%s' % token if token else '/'


def novnc_location():
    """Where / sends the browser: noVNC's page, connecting by itself, sized to the tab."""
    return '/%s?%s' % (NOVNC_PAGE, NOVNC_QUERY)


def url_host(address):
    """address as it goes in a URL ('[::1]' for IPv6)."""
    return '[%s]' % address if ':' in address else address
