"""Fixtures of the multi-host tests: three hosts (network namespaces) and a team on them.

Without root or `ip netns` every test here is skipped, with the reason, so ./ws test counts
them as skipped rather than passed.
"""
import os
import signal

import pytest
from multihost.harness import Team
from multihost.hosts import Hosts, unavailable_reason

PREFIX = 'wsh%d' % os.getpid()  # unique per run: parallel runs never share a namespace


def _interrupted(signum, _frame):
    raise KeyboardInterrupt('signal %d' % signum)


def pytest_configure(config):
    # SIGTERM (a CI cancel, `timeout`) unwinds like Ctrl-C: fixtures remove the namespaces.
    signal.signal(signal.SIGTERM, _interrupted)


@pytest.fixture
def hosts3():
    reason = unavailable_reason()
    if reason:
        pytest.skip('multi-host test: %s' % reason)
    with Hosts(PREFIX, 3) as hosts:
        yield hosts


@pytest.fixture
def team(hosts3, tmp_path):
    team = Team(hosts3, tmp_path)
    yield team
    team.close()
