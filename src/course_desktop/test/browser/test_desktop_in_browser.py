"""The desktop as a student uses it: opened in headless Chromium, typed into, looked at.

Against `./ws desktop` on this machine, or the image (DESKTOP_TEST_IMAGE; course_desktop.testing).
What the page shows is read back from screenshots of the browser: Stage's robots by their
colours, turtlesim's blue canvas and the teleop's trail.
"""
import os
import socket

import pytest
from course_common.ports import free_port
from course_common.processes import descendants, pid_running, process_table
from course_common.waiting import WaitError
from course_desktop.testing import (
    EVENT_DEADLINE_S,
    Browser,
    LocalDesktop,
    colour_spot,
    desktop,
    wait_for,
    wait_for_file,
)

IN_CONTAINER = bool(os.environ.get('DESKTOP_TEST_IMAGE'))
local_only = pytest.mark.skipif(IN_CONTAINER, reason='checks ./ws desktop on this machine')
#: The Stage lesson's robots, by their colours in its world file (blue, red, green, magenta).
ROBOT_COLOURS = ((0, 0, 255), (255, 0, 0), (0, 255, 0), (255, 0, 255))
TURTLESIM_BLUE = (69, 86, 255)  # turtlesim's background
TURTLESIM_PEN = (179, 184, 255)  # turtlesim's default pen
RVIZ_BACKGROUND = (48, 48, 48)  # rviz's default background colour
MIN_ROBOT_PIXELS = 30  # a robot 0.35 m wide at the lesson's 28.8 px/m is about 100 pixels


#: Whose folder the student's is, when root runs these tests against the image: root's own
#: folder would be refused (the image runs no desktop as root), so a host user's ids stand in.
HOST_STUDENT = (1234, 1235)


@pytest.fixture
def workspace(tmp_path):
    """The student's catkin workspace: a folder of this (host) user."""
    path = tmp_path / 'catkin_ws'
    path.mkdir()
    if IN_CONTAINER and os.getuid() == 0:
        os.chown(path, *HOST_STUDENT)
    return str(path)


@pytest.fixture
def browser():
    with Browser() as b:
        yield b


def private_master():
    """A master URI of its own for a desktop on this machine, so a test's roscore never meets
    another (a container has its own network already)."""
    return {} if IN_CONTAINER else {'ROS_MASTER_URI': 'http://localhost:%d' % free_port()}


def test_what_is_typed_in_the_page_runs_in_the_terminal_and_lands_in_the_host_folder(
        workspace, browser):
    with desktop(workspace, env=private_master()) as d:
        browser.open(d.url()).wait_connected()
        browser.type('echo "typed in the browser by $(id -un)" > typed.txt\n')
        text = wait_for_file(os.path.join(workspace, 'typed.txt'))
    assert text.startswith('typed in the browser by ')
    info, folder = os.stat(os.path.join(workspace, 'typed.txt')), os.stat(workspace)
    # The host's files are the folder owner's, the host user's (not root's, in a container).
    assert (info.st_uid, info.st_gid) == (folder.st_uid, folder.st_gid)
    if not IN_CONTAINER:
        assert (folder.st_uid, folder.st_gid) == (os.getuid(), os.getgid())


def test_the_work_survives_a_restart(workspace, browser):
    with desktop(workspace, env=private_master()) as d:
        browser.open(d.url()).wait_connected()
        browser.type('mkdir -p src/kept && echo first run > src/kept/note.txt\n')
        wait_for_file(os.path.join(workspace, 'src', 'kept', 'note.txt'))
    with desktop(workspace, env=private_master()) as d:
        browser.open(d.url()).wait_connected()
        browser.type('cat src/kept/note.txt > seen.txt\n')
        assert wait_for_file(os.path.join(workspace, 'seen.txt')) == 'first run\n'


def test_the_students_package_overlays_the_course_workspace(workspace, browser):
    with desktop(workspace, env=private_master()) as d:
        browser.open(d.url()).wait_connected()
        browser.type('cd src && catkin_create_pkg hello_overlay rospy > /dev/null && cd .. && '
                     'catkin_make > make.log 2>&1; source devel/setup.bash; '
                     '{ rospack find hello_overlay; rospack find multi_sync; } > found.part 2>&1; '
                     'mv found.part found.txt\n')
        found = wait_for_file(os.path.join(workspace, 'found.txt'), timeout_s=180)
    lines = found.split()
    assert len(lines) == 2, found
    assert lines[0].endswith('/src/hello_overlay')
    assert lines[1].endswith('/multi_sync')


def robot_spots(browser):
    """Where each robot of the Stage lesson shows in the page (None where none shows: a
    window may cover it)."""
    picture = browser.screenshot()
    spots = [colour_spot(picture, colour) for colour in ROBOT_COLOURS]
    return [centre if count >= MIN_ROBOT_PIXELS else None for count, centre in spots]


def test_the_stage_lesson_shows_in_the_page_and_its_robots_move_after_go(workspace, browser):
    with desktop(workspace, env=private_master()) as d:
        browser.open(d.url()).wait_connected()
        browser.type('roslaunch multi_sync multi_sync.launch\n')
        start = wait_for(lambda: all(robot_spots(browser)) and robot_spots(browser),
                         EVENT_DEADLINE_S, "Stage's window with its four robots in the page")
        # As the lesson says: the monitor in another terminal (the robots wait for its GO).
        browser.open_terminal()
        browser.type('rosrun multi_sync monitor 4\n')

        def moved():
            return any(now is not None and abs(now[0] - then[0]) + abs(now[1] - then[1]) > 5
                       for now, then in zip(robot_spots(browser), start, strict=True))
        wait_for(moved, EVENT_DEADLINE_S, 'a robot to move in the page after GO')


def test_turtlesim_and_its_teleop_terminal(workspace, browser):
    master = private_master()
    with desktop(workspace, env=master) as d:
        browser.open(d.url()).wait_connected()
        # roscore on the port of the desktop's ROS_MASTER_URI (11311 in a container).
        browser.type('roscore -p "${ROS_MASTER_URI##*:}"\n')
        browser.open_terminal()
        browser.type('rosrun turtlesim turtlesim_node\n')
        try:
            wait_for(lambda: _turtlesim_blue(browser) > 100000, EVENT_DEADLINE_S,
                     "turtlesim's window in the page")
        except WaitError as err:    # say whether roscore came up: turtlesim waits for it
            raise WaitError('%s (%d of its blue pixels show; %s)' % (
                err, _turtlesim_blue(browser), _master_state(master))) from None
        browser.open_terminal()
        browser.type('rosrun turtlesim turtle_teleop_key\n')
        wait_for(lambda: _teleop_drew(browser), EVENT_DEADLINE_S,
                 'the turtle to draw its trail, driven by arrow keys typed in the page')


def test_rviz_shows_its_3d_view(workspace, browser):
    with desktop(workspace, env=private_master()) as d:
        browser.open(d.url()).wait_connected()
        browser.type('roscore -p "${ROS_MASTER_URI##*:}" > /dev/null & rviz\n')
        try:
            wait_for(lambda: colour_spot(browser.screenshot(), RVIZ_BACKGROUND, 4)[0] > 100000,
                     EVENT_DEADLINE_S,
                     "rviz's 3D view (drawn by OpenGL on the desktop's X server)")
        except WaitError as err:    # say whether rviz still runs (Debian's rviz now and then
            raise WaitError('%s (%s)' % (err, _rviz_state(d))) from None  # aborts as it starts)


def _rviz_state(d):
    """Whether an rviz runs under a desktop on this machine (a container's is not seen)."""
    if not hasattr(d, 'pid'):
        return "the container's processes are not seen from here"
    table = process_table()
    names = [os.path.basename(table[pid][1].split(' ')[0]) for pid in descendants(d.pid(), table)]
    return ('rviz runs under the desktop' if 'rviz' in names
            else 'no rviz process under the desktop: it exited or crashed')


def _turtlesim_blue(browser):
    return colour_spot(browser.screenshot(), TURTLESIM_BLUE, 12)[0]


def _master_state(env):
    """Whether the desktop's master answers (from this machine: not the container's)."""
    uri = env.get('ROS_MASTER_URI')
    if uri is None:
        return "the container's master is not reachable from here"
    import rosgraph
    try:
        rosgraph.Master('/desktop_test', master_uri=uri).getPid()
    except (OSError, rosgraph.MasterException) as err:
        return 'no master answers at %s: %s' % (uri, err)
    return 'its master answers at %s' % uri


def _teleop_drew(browser):
    from selenium.webdriver.common.keys import Keys
    browser.type(Keys.ARROW_UP * 3)
    return colour_spot(browser.screenshot(), TURTLESIM_PEN, 12)[0] > 20


def test_a_page_without_the_token_or_with_a_wrong_one_shows_no_desktop(workspace, browser):
    token_args = [] if IN_CONTAINER else ['--listen', '0.0.0.0']
    with desktop(workspace, *token_args, env=private_master()) as d:
        url = d.url()
        assert '?token=' in url
        bare = url.split('?', 1)[0]
        browser.open(bare)
        assert 'needs its token' in browser.page_text()
        browser.open(bare + 'vnc.html?autoconnect=1')
        assert 'needs its token' in browser.page_text()
        browser.open(url + 'x')
        assert 'wrong token' in browser.page_text()
        assert not browser.connected()
        browser.open(url).wait_connected()
        # The token became a cookie: the page opens again without it in the URL.
        browser.open(bare).wait_connected()


@local_only
def test_ctrl_c_stops_everything_it_started_even_what_left_its_process_group(
        workspace, browser):
    d = LocalDesktop(workspace, env=private_master()).start()
    try:
        browser.open(d.url()).wait_connected()
        browser.type('roscore -p "${ROS_MASTER_URI##*:}" > /dev/null & '
                     '(setsid sleep 600 &); sleep 601 &\n')

        def started():
            table = process_table()
            tree = {pid: table[pid][1] for pid in descendants(d.pid(), table)}
            names = ' '.join(tree.values())
            return tree if all(n in names for n in ('rosmaster', 'sleep 600', 'sleep 601')) \
                else None
        tree = wait_for(started, EVENT_DEADLINE_S, "roscore and the sleeps under the desktop")
    finally:
        code = d.stop()
    assert code == 0, d.output()
    survivors = [pid for pid in tree if pid_running(pid)]
    assert not survivors, [tree[pid] for pid in survivors]


@local_only
def test_a_taken_port_is_one_clear_message_and_exit_1(workspace):
    with socket.socket() as taken:
        taken.bind(('127.0.0.1', 0))
        taken.listen()
        port = taken.getsockname()[1]
        d = LocalDesktop(workspace, port=port).start()
        code = d.process.wait_exit(60)
    assert code == 1
    assert 'port %d is taken' % port in d.output()


@local_only
@pytest.mark.parametrize('args, message', [
    (['--listen', 'no-such-host.invalid'], 'not an address this machine can serve on'),
    (['--workspace', '/proc/version/catkin_ws'], 'cannot create your workspace'),
])
def test_bad_places_are_one_clear_message_and_exit_1(workspace, args, message):
    d = LocalDesktop(workspace, *args).start()
    assert d.process.wait_exit(60) == 1
    assert message in d.output()
    assert 'Traceback' not in d.output()


@local_only
def test_a_short_token_is_refused_before_anything_starts(workspace):
    d = LocalDesktop(workspace, '--token', 'short').start()
    assert d.process.wait_exit(60) == 2
    assert 'at least 8 characters' in d.output()
