"""A terminal in turtlesim teleop's raw mode (termios only, no ROS)."""

import termios


class RawTerminal:
    """Context manager: the terminal on fd in non-canonical, no-echo mode, one byte per read.

    The previous settings come back on exit, whatever ends the block (q, SIGINT, shutdown).
    """

    def __init__(self, fd):
        self._fd = fd
        self._saved = None

    def __enter__(self):
        self._saved = termios.tcgetattr(self._fd)
        raw = termios.tcgetattr(self._fd)
        raw[3] &= ~(termios.ICANON | termios.ECHO)  # lflags
        raw[6][termios.VMIN] = 1
        raw[6][termios.VTIME] = 0
        termios.tcsetattr(self._fd, termios.TCSANOW, raw)
        return self

    def __exit__(self, *exc):
        termios.tcsetattr(self._fd, termios.TCSANOW, self._saved)
        return False
