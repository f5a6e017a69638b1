"""The desktop's test helpers: a desktop started as a student starts it (./ws desktop on this
machine, or `docker run ... desktop` of an image), and a headless Chromium that opens it,
types into it and reads its picture back.

Used by test/browser (pytest) and bench/desktop_bench.py. Which desktop: `./ws desktop` by
default; with DESKTOP_TEST_IMAGE set, that image through DESKTOP_TEST_ENGINE (docker, podman).
Which browser: Debian's chromium and chromedriver; or a chromedriver already serving at
DESKTOP_TEST_WEBDRIVER (a URL: CI runs the image's own Chromium and chromedriver in a container
of its own, for the architectures a runner has no browser for).
"""
import io
import os
import re
import shutil
import subprocess

from course_common.ports import free_port
from course_common.processes import ChildProcess
from course_common.waiting import WaitError, wait_for

START_DEADLINE_S = 60.0  # a desktop up, a page connected (a cold container start is slower)
EVENT_DEADLINE_S = 60.0  # a window to appear, a command typed to finish
URL_LINE = re.compile(r'^desktop: open (\S+)$')
CHROME_FLAGS = ('--headless=new', '--disable-gpu', '--disable-quic', '--no-first-run',
                '--disable-background-networking', '--disable-component-update',
                '--disable-sync', '--disable-dev-shm-usage')
MODIFIER_KEYS = {'ctrl': lambda keys: keys.CONTROL, 'alt': lambda keys: keys.ALT,
                 'shift': lambda keys: keys.SHIFT}
WHITE = (255, 255, 255)  # a terminal's background
#: An 80 x 24 terminal is about 720 x 450 = 320,000 pixels; a window it covers may have been
#: half white (Stage's floor), so half of that at least is new.
NEW_TERMINAL_PIXELS = 100000
WINDOW = (1600, 1000)  # the browser window (a laptop's); noVNC sizes the remote screen to its page


def workspace_root():
    """The course workspace's checkout (where ./ws is), from the sourced devel space."""
    setup = os.environ.get('COURSE_WS_SETUP')
    if setup:
        return os.path.dirname(os.path.dirname(setup))
    here = os.path.dirname(os.path.abspath(__file__))
    while here != '/' and not os.path.exists(os.path.join(here, 'ws')):
        here = os.path.dirname(here)
    return here


class _Desktop:
    """A desktop's command (its `process`, a ChildProcess) on `port`; a context manager."""

    def __init__(self, workspace, port):
        self.workspace = workspace
        self.port = port or free_port()
        self.process = None

    def start(self):
        self.process.start()
        return self

    def url(self, timeout_s=START_DEADLINE_S):
        """The URL it printed to open (once it is ready), as this machine reaches it; or
        WaitError with its output."""
        try:
            printed = wait_for(lambda: _printed_url(self.process.lines()), timeout_s,
                               'the desktop to print its URL', alive=self.process.alive)
        except WaitError as err:
            raise WaitError('%s; it printed:\n%s' % (err, self.process.tail())) from None
        return self._reached(printed)

    def _reached(self, printed):
        return printed

    def output(self):
        return self.process.output()

    def stop(self):
        """SIGINT (Ctrl-C), as a student stops it; returns its exit code."""
        return self.process.stop()

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


class LocalDesktop(_Desktop):
    """`./ws desktop ARGS` on this machine, on a free port."""

    def __init__(self, workspace, *args, port=None, env=None):
        super().__init__(workspace, port)
        argv = [os.path.join(workspace_root(), 'ws'), 'desktop', '--port', str(self.port),
                '--workspace', workspace] + list(args)
        self.process = ChildProcess(argv, env=env, stop_timeout_s=30.0)

    def pid(self):
        return self.process.pid


class ContainerDesktop(_Desktop):
    """`ENGINE run --rm -p 127.0.0.1:PORT:6080 -v WORKSPACE:/home/student/catkin_ws IMAGE
    desktop`, the README's command."""

    def __init__(self, workspace, *args, port=None, image=None, engine=None, env=None):
        super().__init__(workspace, port)
        self.engine = engine or os.environ.get('DESKTOP_TEST_ENGINE', 'docker')
        self.name = 'course-desktop-test-%d' % self.port
        argv = [self.engine, 'run', '--rm', '--name', self.name,
                '-p', '127.0.0.1:%d:6080' % self.port,
                '-v', '%s:/home/student/catkin_ws' % workspace]
        for key, value in (env or {}).items():
            argv += ['-e', '%s=%s' % (key, value)]
        argv += [image or os.environ['DESKTOP_TEST_IMAGE'], 'desktop'] + list(args)
        self.process = ChildProcess(argv, stop_timeout_s=60.0)

    def _reached(self, printed):
        # Inside, it names its own port; outside, the port published for it.
        return re.sub(r'^http://localhost:\d+', 'http://localhost:%d' % self.port, printed)

    def stop(self):
        """`docker stop` (SIGTERM to the desktop), then the run command's exit code."""
        subprocess.run([self.engine, 'stop', '-t', '30', self.name], check=False,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=90)
        return self.process.stop()


def desktop(workspace, *args, **kwargs):
    """The desktop under test: the image's if DESKTOP_TEST_IMAGE is set, else ./ws desktop."""
    if os.environ.get('DESKTOP_TEST_IMAGE'):
        return ContainerDesktop(workspace, *args, **kwargs)
    return LocalDesktop(workspace, *args, **kwargs)


def _printed_url(lines):
    for line in lines:
        match = URL_LINE.match(line)
        if match:
            return match.group(1)
    return None


class Browser:
    """Headless Chromium driven by Selenium; a context manager."""

    def __init__(self, size=WINDOW):
        from selenium import webdriver
        from selenium.webdriver.chrome.options import Options
        from selenium.webdriver.chrome.service import Service
        options = Options()
        # Chromium's sandbox refuses root (this machine's tests, a container's browser).
        for flag in CHROME_FLAGS + ('--no-sandbox', '--window-size=%d,%d' % size):
            options.add_argument(flag)
        remote = os.environ.get('DESKTOP_TEST_WEBDRIVER')
        if remote:
            self.driver = webdriver.Remote(command_executor=remote, options=options)
            return
        options.binary_location = shutil.which('chromium') or '/usr/bin/chromium'
        service = Service(shutil.which('chromedriver') or '/usr/bin/chromedriver')
        self.driver = webdriver.Chrome(service=service, options=options)

    def open(self, url):
        self.driver.get(url)
        return self

    def connected(self):
        """True while noVNC shows the desktop (its page's 'connected' state)."""
        return self.driver.execute_script(
            "return document.documentElement.classList.contains('noVNC_connected')")

    def wait_connected(self, timeout_s=START_DEADLINE_S):
        return wait_for(self.connected, timeout_s, 'noVNC to connect to the desktop')

    def type(self, text):
        """Keys into the page's focused element (noVNC's canvas), as a person types."""
        from selenium.webdriver.common.action_chains import ActionChains
        ActionChains(self.driver).send_keys(text).perform()

    def hotkey(self, *modifiers_and_key):
        """A chord such as ('ctrl', 'alt', 't'): modifiers held while the last key is pressed."""
        from selenium.webdriver.common.action_chains import ActionChains
        from selenium.webdriver.common.keys import Keys
        *modifiers, key = modifiers_and_key
        chain = ActionChains(self.driver)
        held = [MODIFIER_KEYS[m](Keys) for m in modifiers]
        for k in held:
            chain.key_down(k)
        chain.send_keys(key)
        for k in reversed(held):
            chain.key_up(k)
        chain.perform()

    def open_terminal(self, timeout_s=EVENT_DEADLINE_S):
        """Ctrl+Alt+T, then waits until the new terminal shows (its white page adds at least
        NEW_TERMINAL_PIXELS to the screen), so that what is typed next goes to it."""
        before = colour_spot(self.screenshot(), WHITE, 3)[0]
        self.hotkey('ctrl', 'alt', 't')
        wait_for(lambda: colour_spot(self.screenshot(), WHITE, 3)[0] - before
                 > NEW_TERMINAL_PIXELS, timeout_s, 'a new terminal to open in the page')

    def page_text(self):
        return self.driver.find_element('tag name', 'body').text

    def screenshot(self):
        """The page as the student sees it, as a PIL RGB image."""
        from PIL import Image
        return Image.open(io.BytesIO(self.driver.get_screenshot_as_png())).convert('RGB')

    def close(self):
        self.driver.quit()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def wait_for_file(path, timeout_s=EVENT_DEADLINE_S, what=None):
    """The text of path once it exists and ends in a newline: a command typed has written it
    (several lines: write them elsewhere and `mv` the file into place)."""
    def finished():
        try:
            with open(path, encoding='utf-8') as f:
                text = f.read()
        except OSError:
            return None
        return text if text.endswith('\n') else None
    return wait_for(finished, timeout_s, what or 'the file %s' % path)


def colour_spot(image, rgb, tolerance=40, box=None):
    """(how many pixels, their centroid (x, y) or None) of image within `tolerance` of rgb in
    every channel, inside box (left, top, right, bottom) if given. The tolerance absorbs
    VNC's JPEG encoding of the screen."""
    import numpy as np
    pixels = np.asarray(image if box is None else image.crop(box), dtype=np.int16)
    near = (np.abs(pixels - np.array(rgb, dtype=np.int16)) <= tolerance).all(axis=2)
    count = int(near.sum())
    if not count:
        return 0, None
    ys, xs = np.nonzero(near)
    left, top = (0, 0) if box is None else box[:2]
    return count, (float(xs.mean()) + left, float(ys.mean()) + top)
