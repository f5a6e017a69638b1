"""rviz_snapshot: rviz with a configuration file on its own Xvfb screen, and a PNG of it.

Used by the rviz tests and by anyone who wants a picture of a running lesson without a display:
    rosrun course_common rviz_snapshot $(rospack find convoy)/rviz/convoy.rviz --out convoy.png
It starts Xvfb on a free display and rviz on it with Mesa's software renderer (llvmpipe), waits
until rviz subscribes to every topic the file names and its view shows the arena, the robots
and their labels (rviz_screen), saves the screen, and stops both. Needs a running master,
and the lesson's pose_to_tf and lesson_markers.
"""

import argparse
import os
import sys

import numpy as np
import rosgraph
from PIL import Image, ImageGrab

from course_common.processes import ChildProcess
from course_common.rviz.config import display_topics
from course_common.rviz.screen import shows_lesson
from course_common.waiting import wait_for
from course_common.xvfb import Xvfb

SCREEN = (1024, 800)
START_DEADLINE_S = 60.0  # rviz with software GL on a loaded 2-core machine
# Debian's rviz 1.14.19 now and then aborts as it starts ("free(): invalid next size", once in
# some 35 starts beside the whole suite; once just after subscribing): a death by a signal
# while a view is awaited is tried once more, within the same deadline; a second one, or an
# exit, fails.
CRASH_RESTARTS = 1


class RvizOnXvfb:
    """rviz showing `config_path` on a private Xvfb screen; a context manager.

    `node_name` is rviz's node name on the master (unique: the test asks the master about it).
    """

    def __init__(self, config_path, node_name=None):
        node_name = node_name or 'rviz_snapshot_%d' % os.getpid()
        with open(config_path) as f:
            self.topics = display_topics(f.read())
        self.node_name = '/' + node_name.lstrip('/')
        self._xvfb = Xvfb(SCREEN)
        self.display = self._xvfb.display
        self._argv = ['rviz', '-d', config_path, '__name:=' + node_name.lstrip('/')]
        self.restarts = 0
        try:
            self._rviz = self._start_rviz()
        except OSError:
            self._xvfb.close()
            raise

    def _start_rviz(self):
        return ChildProcess(self._argv, stop_timeout_s=10.0,
                            env={'DISPLAY': self.display, 'LIBGL_ALWAYS_SOFTWARE': '1'}).start()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self._rviz.stop()
        self._xvfb.close()

    def log(self):
        return self._rviz.output()

    def running(self):
        return self._rviz.alive()

    def subscriptions(self):
        """The topics rviz's node subscribes to, as the master reports them."""
        _pubs, subs, _srvs = rosgraph.Master('/rviz_snapshot').getSystemState()
        return sorted(topic for topic, nodes in subs if self.node_name in nodes)

    def missing_topics(self):
        """Topics the file names that rviz does not (yet) subscribe to."""
        return sorted(set(self.topics) - set(self.subscriptions()))

    def grab(self):
        """The screen as an H x W x 3 uint8 array."""
        return np.asarray(ImageGrab.grab(xdisplay=self.display).convert('RGB'))

    def alive_and(self, check):
        """check() while rviz runs, for wait_for. rviz's death by a signal (its own crash)
        starts it again, CRASH_RESTARTS times, and returns None: the wait goes on. An exit of
        its own, or one crash too many, raises naming the exit code and rviz's last lines."""
        if not self.running():
            code = self._rviz.returncode
            if code is not None and code < 0 and self.restarts < CRASH_RESTARTS:
                # rviz's own crash as it starts (a signal, not an exit of its own): once more.
                print('rviz died of signal %d; started again:\n%s' % (-code, self.log()[-2000:]))
                self.restarts += 1
                self._rviz = self._start_rviz()
                return None
            raise AssertionError('rviz exited (code %s):\n%s' % (code, self.log()[-2000:]))
        return check()

    def wait_subscribed(self, timeout_s=START_DEADLINE_S):
        wait_for(lambda: self.alive_and(lambda: not self.missing_topics()), timeout_s,
                 'rviz subscribed to %s' % ', '.join(self.topics))

    def wait_lesson_drawn(self, robots, labels, timeout_s=START_DEADLINE_S):
        """Waits until the screen shows the arena, `robots` robots and `labels` texts (names,
        gap labels); returns the screenshot."""
        def drawn():
            shot = self.grab()
            return [shot] if shows_lesson(shot, robots, labels) else None
        return wait_for(lambda: self.alive_and(drawn), timeout_s,
                        'rviz drawing the arena, %d robot(s) and %d label(s)' % (robots, labels))[0]

    def capture(self, out_path, robots, labels, timeout_s=START_DEADLINE_S):
        """Waits until rviz is subscribed and shows the lesson (each wait up to timeout_s),
        saves the screen to out_path (PNG) and returns it as an array."""
        self.wait_subscribed(timeout_s)
        shot = self.wait_lesson_drawn(robots, labels, timeout_s)
        Image.fromarray(shot).save(out_path)
        return shot


def snapshot(config_path, out_path, robots, labels, timeout_s=START_DEADLINE_S):
    """Saves a PNG of rviz showing config_path on the running lesson; returns the rviz log."""
    with RvizOnXvfb(config_path) as rviz:
        rviz.capture(out_path, robots, labels, timeout_s)
        return rviz.log()


def run(argv):
    """The command line; returns the exit code."""
    parser = argparse.ArgumentParser(
        prog='rviz_snapshot', description='A PNG of rviz showing a lesson, without a display.')
    parser.add_argument('config',
                        help='an .rviz file, e.g. $(rospack find convoy)/rviz/convoy.rviz')
    parser.add_argument('--out', required=True, help='the PNG to write')
    parser.add_argument('--robots', type=int, default=1,
                        help='wait until this many robots are drawn (default 1)')
    parser.add_argument('--labels', type=int, default=None,
                        help='and this many texts: names, gap labels (default: --robots)')
    parser.add_argument('--timeout', type=float, default=START_DEADLINE_S,
                        help='seconds to wait for rviz (default %(default)s)')
    args = parser.parse_args(argv)
    if not os.path.isfile(args.config):
        parser.error('no such file: %s' % args.config)
    labels = args.robots if args.labels is None else args.labels
    if args.robots < 0 or labels < 0 or args.timeout <= 0:
        parser.error('--robots and --labels must be >= 0 and --timeout > 0')
    try:
        rosgraph.Master('/rviz_snapshot').getPid()
    except OSError:
        print('rviz_snapshot: no master at %s: start the lesson first'
              % rosgraph.get_master_uri(), file=sys.stderr)
        return 1
    try:
        snapshot(args.config, args.out, args.robots, labels, args.timeout)
    except (AssertionError, ValueError) as err:
        print('rviz_snapshot: %s' % err, file=sys.stderr)
        return 1
    print(os.path.abspath(args.out))
    return 0


def main():
    sys.exit(run(sys.argv[1:]))
