"""Unit tests for RawTerminal (terminal): modes set on entry, restored on exit, on a pty."""

import os
import termios

import pytest
from turtle_lite.terminal import RawTerminal


@pytest.fixture
def pty_slave():
    master, slave = os.openpty()
    yield slave
    os.close(master)
    os.close(slave)


def test_raw_terminal_sets_and_restores_modes(pty_slave):
    before = termios.tcgetattr(pty_slave)
    with RawTerminal(pty_slave):
        raw = termios.tcgetattr(pty_slave)
        assert not raw[3] & (termios.ICANON | termios.ECHO)
        assert (raw[6][termios.VMIN], raw[6][termios.VTIME]) == (1, 0)
    assert termios.tcgetattr(pty_slave) == before


def test_raw_terminal_restores_on_error(pty_slave):
    before = termios.tcgetattr(pty_slave)
    with pytest.raises(KeyboardInterrupt), RawTerminal(pty_slave):
        raise KeyboardInterrupt
    assert termios.tcgetattr(pty_slave) == before
