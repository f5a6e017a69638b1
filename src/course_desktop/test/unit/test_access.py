"""course_desktop.access: who may see the desktop."""
import pytest
from course_desktop.access import (
    AccessError,
    AccessPolicy,
    check_token,
    cookie_value,
    is_loopback,
    new_token,
    novnc_location,
    query_token,
    same_origin,
    split_host,
    start_path,
)

TOKEN = 'a-token-of-the-desktop'


def ws_headers(host, origin, **more):
    return dict({'Host': host, 'Origin': origin, 'Upgrade': 'websocket'}, **more)


@pytest.mark.parametrize('address, loopback', [
    ('127.0.0.1', True), ('127.8.9.10', True), ('::1', True), ('localhost', True),
    ('0.0.0.0', False), ('::', False), ('192.168.1.5', False), ('example.org', False),
    ('', False), ('localhost.evil.example', False),
])
def test_loopback_addresses(address, loopback):
    assert is_loopback(address) is loopback


@pytest.mark.parametrize('header, parts', [
    ('127.0.0.1:6080', ('127.0.0.1', '6080')), ('localhost', ('localhost', None)),
    ('[::1]:6080', ('::1', '6080')), ('[::1]', ('::1', None)),
    ('LocalHost:80', ('localhost', '80')),
])
def test_host_header_split(header, parts):
    assert split_host(header) == parts


def test_new_tokens_are_long_random_and_usable():
    tokens = {new_token() for _ in range(50)}
    assert len(tokens) == 50
    for token in tokens:
        assert check_token(token) == token and len(token) >= 32


@pytest.mark.parametrize('token, message', [
    ('short', 'at least 8'), ('has space in it', 'only letters'), ('semi;colon;x', 'only letters'),
    ('percent%20x', 'only letters'),
])
def test_bad_tokens_say_why(token, message):
    with pytest.raises(AccessError, match=message):
        check_token(token)


class TestLoopbackWithoutToken:
    policy = AccessPolicy(6080)

    @pytest.mark.parametrize('host', ['127.0.0.1:6080', 'localhost:6080', '[::1]:6080'])
    def test_pages_from_a_loopback_name_are_served(self, host):
        assert self.policy.judge('/', {'Host': host}).allowed
        assert self.policy.judge('/vnc.html', {'Host': host}).allowed

    @pytest.mark.parametrize('host', ['evil.example:6080', '192.168.1.5:6080', '', 'x'])
    def test_any_other_host_name_is_refused(self, host):
        # A name of another site rebound to 127.0.0.1 arrives with that site's Host.
        verdict = self.policy.judge('/', {'Host': host})
        assert not verdict.allowed and verdict.status == 403
        assert 'loopback' in verdict.reason

    def test_the_websocket_from_its_own_page_opens(self):
        assert self.policy.judge('/websockify', ws_headers('127.0.0.1:6080',
                                                           'http://127.0.0.1:6080')).allowed

    @pytest.mark.parametrize('origin', [None, 'http://evil.example', 'http://127.0.0.1:9999',
                                        'null', 'file://', 'http://localhost:6080'])
    def test_a_websocket_from_any_other_page_is_refused(self, origin):
        headers = ws_headers('127.0.0.1:6080', origin)
        if origin is None:
            del headers['Origin']
        verdict = self.policy.judge('/websockify', headers)
        assert not verdict.allowed and 'its own page' in verdict.reason

    def test_no_cookie_is_set(self):
        assert self.policy.judge('/', {'Host': 'localhost:6080'}).set_cookie == ''


class TestWithToken:
    policy = AccessPolicy(6080, TOKEN)
    host = {'Host': '192.168.1.5:6080'}

    def test_the_token_in_the_url_lets_in_and_becomes_a_cookie(self):
        verdict = self.policy.judge(start_path(TOKEN), self.host)
        assert verdict.allowed
        assert verdict.set_cookie == ('course_desktop_6080=%s; Path=/; HttpOnly; SameSite=Strict'
                                      % TOKEN)

    def test_the_cookie_lets_in_without_the_token_in_the_url(self):
        headers = dict(self.host, Cookie='other=1; course_desktop_6080=%s' % TOKEN)
        verdict = self.policy.judge('/vnc.html', headers)
        assert verdict.allowed and verdict.set_cookie == ''

    def test_a_page_without_token_or_cookie_is_refused_and_told_where_to_look(self):
        verdict = self.policy.judge('/vnc.html', self.host)
        assert not verdict.allowed and verdict.status == 403
        assert 'needs its token' in verdict.reason

    @pytest.mark.parametrize('path, cookie', [
        ('/?token=wrong-token-1', None), ('/?token=', None),
        ('/?token=%s' % TOKEN[:-1], None),
    ])
    def test_a_wrong_token_is_refused(self, path, cookie):
        verdict = self.policy.judge(path, self.host)
        assert not verdict.allowed and 'token' in verdict.reason

    @pytest.mark.parametrize('cookie', [
        'course_desktop_6080=wrong', 'course_desktop_6081=%s' % TOKEN, 'garbage;;==',
        'course_desktop_6080',
    ])
    def test_a_wrong_or_foreign_cookie_is_refused(self, cookie):
        assert not self.policy.judge('/vnc.html', dict(self.host, Cookie=cookie)).allowed

    def test_the_websocket_needs_the_cookie_and_its_own_origin(self):
        cookie = 'course_desktop_6080=%s' % TOKEN
        own = ws_headers('192.168.1.5:6080', 'http://192.168.1.5:6080', Cookie=cookie)
        assert self.policy.judge('/websockify', own).allowed
        foreign = ws_headers('192.168.1.5:6080', 'http://evil.example', Cookie=cookie)
        assert not self.policy.judge('/websockify', foreign).allowed
        without = ws_headers('192.168.1.5:6080', 'http://192.168.1.5:6080')
        assert not self.policy.judge('/websockify', without).allowed

    def test_each_port_has_its_own_cookie(self):
        assert AccessPolicy(6081, TOKEN).cookie_name != self.policy.cookie_name


@pytest.mark.parametrize('origin, host, same', [
    ('http://a:1', 'a:1', True), ('https://a:1', 'a:1', True), ('HTTP://A:1', 'a:1', True),
    ('http://a:1', 'a:2', False), ('ws://a:1', 'a:1', False), ('', 'a:1', False),
    ('http://a:1', '', False),
])
def test_same_origin(origin, host, same):
    assert same_origin({'Origin': origin, 'Host': host}) is same


def test_query_token_and_cookie_value():
    assert query_token('/?token=abc&x=1') == 'abc'
    assert query_token('/vnc.html?autoconnect=1') is None
    assert cookie_value('a=1; b=2', 'b') == '2'
    assert cookie_value(None, 'b') is None
    assert cookie_value('a=1', 'b') is None


def test_the_start_page_leads_to_novnc_connecting_by_itself_sized_to_the_tab():
    assert start_path(None) == '/'
    assert start_path('tok') == '/?token=tok'
    location = novnc_location()
    assert location.startswith('/vnc.html?')
    for setting in ('autoconnect=1', 'resize=remote', 'reconnect=1'):
        assert setting in location
