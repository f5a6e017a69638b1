"""Xvfb: a private X server for windows nobody sees (rviz_snapshot, the GUI tests)."""
import os

from course_common.processes import ChildProcess
from course_common.waiting import WaitError, wait_for

START_TIMEOUT_S = 30.0  # Xvfb starts in well under a second; a loaded machine may take longer
SCREEN = (1024, 800)  # pixels: room for rviz's panels and view, or a 500 x 500 canvas


def display_number(lines):
    """The display number Xvfb -displayfd 1 wrote (a line of digits alone), or None yet.

    Its warnings go to the same output, so any other line is passed over.
    """
    return next((line.strip() for line in lines if line.strip().isdigit()), None)


class Xvfb:
    """Xvfb on a display number it picks itself (-displayfd: never one in use); a context
    manager. `display` is ':N'; env() is an environment for a program to open it."""

    def __init__(self, size=SCREEN, timeout_s=START_TIMEOUT_S):
        self._proc = ChildProcess(['Xvfb', '-displayfd', '1', '-screen', '0',
                                   '%dx%dx24' % tuple(size), '-nolisten', 'tcp'],
                                  stop_timeout_s=10.0).start()
        try:
            number = wait_for(lambda: display_number(self._proc.lines()), timeout_s,
                              'Xvfb to report its display number', alive=self._proc.alive)
        except WaitError as err:
            self._proc.stop()
            raise WaitError('%s; Xvfb said:\n%s' % (err, self._proc.tail())) from None
        self.display = ':' + number

    def env(self, **extra):
        """This process's environment with DISPLAY set to this server (and extra)."""
        return dict(os.environ, DISPLAY=self.display, **extra)

    def alive(self):
        return self._proc.alive()

    def close(self):
        self._proc.stop()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
