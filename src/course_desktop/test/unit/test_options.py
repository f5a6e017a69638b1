"""course_desktop.options: the desktop's command line."""
import errno
import http.server
import socket
import threading

import pytest
from course_desktop.cli import DesktopError, bind_error_message, self_check
from course_desktop.options import DEFAULT_PORT, TOKEN_ENV, parse_options

SETUP = ['--course-setup', '/ws/devel/setup.bash']


def parse(*argv, environ=None):
    return parse_options(list(argv) + SETUP, environ=environ or {})


def test_defaults_are_loopback_without_a_token():
    options = parse()
    assert (options.listen, options.port, options.token) == ('127.0.0.1', DEFAULT_PORT, None)
    assert options.workspace.endswith('/catkin_ws')
    assert options.geometry == '1280x800'


@pytest.mark.parametrize('address', ['0.0.0.0', '::', '192.168.1.5', 'myhost'])
def test_beyond_loopback_a_token_is_made(address):
    options = parse('--listen', address)
    assert options.token and len(options.token) >= 32
    assert parse('--listen', address).token != options.token


def test_a_token_given_is_kept_on_any_address():
    assert parse('--token', 'my-class-password').token == 'my-class-password'
    assert parse('--listen', '0.0.0.0', '--token', 'my-class-password').token == \
        'my-class-password'


def test_the_token_from_the_environment():
    assert parse('--listen', '0.0.0.0', environ={TOKEN_ENV: 'from-the-env-1'}).token == \
        'from-the-env-1'
    assert parse('--token', 'the-flag-wins', environ={TOKEN_ENV: 'from-the-env-1'}).token == \
        'the-flag-wins'


def test_the_workspace_is_made_absolute(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert parse('--workspace', 'mine').workspace == str(tmp_path / 'mine')


@pytest.mark.parametrize('argv, message', [
    (['--port', '0'], '--port must be 1..65535'),
    (['--port', '70000'], '--port must be 1..65535'),
    (['--port', 'http'], 'invalid int value'),
    (['--geometry', '100x100'], '--geometry must be WIDTHxHEIGHT'),
    (['--geometry', 'big'], '--geometry must be WIDTHxHEIGHT'),
    (['--token', 'short'], 'at least 8 characters'),
    (['--token', 'with space x'], 'only letters'),
    (['--no-such-option'], 'unrecognized arguments'),
])
def test_bad_values_exit_2_with_what_was_wrong(argv, message, capsys):
    with pytest.raises(SystemExit) as exit_:
        parse(*argv)
    assert exit_.value.code == 2
    assert message in capsys.readouterr().err


def test_without_the_course_setup_it_says_so(capsys):
    with pytest.raises(SystemExit):
        parse_options([], environ={})
    assert '--course-setup is missing' in capsys.readouterr().err


@pytest.mark.parametrize('err, words', [
    (OSError(errno.EADDRINUSE, 'in use'), 'port 6080 is taken on 127.0.0.1'),
    (OSError(errno.EADDRNOTAVAIL, 'no'), 'is not an address of this machine'),
    (OSError(errno.EACCES, 'denied'), 'ports below 1024 need root'),
    (socket.gaierror(-2, 'Name or service not known'), 'not an address this machine can serve'),
    (OSError(errno.ENOBUFS, 'No buffer space'), 'cannot serve on 127.0.0.1:6080: No buffer'),
])
def test_a_failed_bind_says_what_to_do(err, words):
    assert words in bind_error_message(err, '127.0.0.1', 6080)


def test_a_page_that_cannot_be_reached_is_a_clear_error():
    with socket.socket() as closed:
        closed.bind(('127.0.0.1', 0))
        port = closed.getsockname()[1]
    with pytest.raises(DesktopError, match='cannot be reached from this machine'):
        self_check('http://127.0.0.1:%d/' % port)


def test_a_page_that_answers_something_else_is_a_clear_error():
    class Other(http.server.BaseHTTPRequestHandler):
        def do_GET(self):
            self.send_response(200)
            self.send_header('Content-Length', '0')
            self.end_headers()

        def log_message(self, *args):
            pass
    server = http.server.HTTPServer(('127.0.0.1', 0), Other)
    thread = threading.Thread(target=server.handle_request, daemon=True)
    thread.start()
    try:
        with pytest.raises(DesktopError, match='answered HTTP 200'):
            self_check('http://127.0.0.1:%d/' % server.server_address[1])
    finally:
        thread.join(10)
        server.server_close()
