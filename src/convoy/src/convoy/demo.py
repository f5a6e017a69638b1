"""convoy_demo: the workspace's main demo, the convoy with its autopilot leader, headless.

rosrun convoy convoy_demo --out DIR [--duration S] [--n N] [--gui]
Starts the convoy launch file (convoy.launch for 3 robots, convoy_chain.launch otherwise) with
its own master on a free port, records every pose and cmd_vel with `rosbag record` for a fixed
time, saves the simulator's canvas and a picture of rviz showing the convoy (rviz/convoy.rviz on
a private Xvfb), stops everything, then makes the summary table and the trail and gap plots
from the bag with bag_report's code.
"""
import os
import sys
import time

import rosgraph
import rospkg
import rospy
from course_common.demo_cli import bounded, demo_main, demo_parser
from course_common.private_launch import PrivateMasterLaunch
from course_common.rviz.snapshot import snapshot
from course_common.startup import init_node
from course_common.waiting import WaitError, wait_for
from course_msgs.srv import SaveImage

from convoy.bag_report import BagError, summarise_bag, write_figures
from convoy.harness import POLL_S, HarnessError, launch_for
from convoy.recording import BagRecorder, convoy_topics
from convoy.report import table_lines

DEFAULT_DURATION_S = 30.0  # with start-up and shutdown, one demo stays well under a minute
MAX_DURATION_S = 600.0
STARTUP_TIMEOUT_S = 30.0  # a loaded 2-core machine can take ~10 s to bring up 13 processes
SERVICE_TIMEOUT_S = 10.0


def parse_args(argv):
    """Parses and checks the command line (argparse exits 2 with a message on bad input)."""
    parser = demo_parser('convoy_demo', 'Run the convoy with its autopilot leader, headless, '
                         'and write a picture of the trails and a plot of the gaps.',
                         'directory for the bag, the PNGs and the logs')
    parser.add_argument('--duration', type=bounded(float, 1.0, MAX_DURATION_S, 's'),
                        default=DEFAULT_DURATION_S,
                        help='seconds to record once every robot is up (default %(default)s)')
    parser.add_argument('--n', type=bounded(int, 2, 10), default=3,
                        help='robots in the convoy, leader included, 2..10 (default 3: the '
                        "course's convoy.launch)")
    parser.add_argument('--gui', action='store_true', help="open the simulator's window")
    return parser.parse_args(argv)


def save_canvas(path):
    """Asks the simulator for a PNG of its canvas; returns (path written, None) or (None, error)."""
    try:
        rospy.wait_for_service('/turtlesim/save_image', SERVICE_TIMEOUT_S)
        return rospy.ServiceProxy('/turtlesim/save_image', SaveImage)(path).path, None
    except (rospy.ROSException, rospy.ServiceException) as err:
        return None, str(err)


def save_rviz(path, n_robots):
    """rviz's view of the running convoy as a PNG; returns (path written, None) or (None, error)."""
    try:
        config = os.path.join(rospkg.RosPack().get_path('convoy'), 'rviz', 'convoy.rviz')
        # Labels: every robot's name and every follower's gap.
        snapshot(config, path, robots=n_robots, labels=2 * n_robots - 1)
        return path, None
    except (AssertionError, OSError, ValueError, rospkg.ResourceNotFound) as err:
        return None, str(err)


def running(launch, recorder):
    """An alive check for wait_for: the launch and the bag recorder are both still up."""
    return lambda: launch.alive() and recorder.alive()


def run(args):
    """Runs the demo; returns the process exit code."""
    os.makedirs(args.out, exist_ok=True)
    canvas_png = os.path.join(args.out, 'convoy_canvas.png')
    bag_path = os.path.join(args.out, 'convoy.bag')
    rviz_png = os.path.join(args.out, 'convoy_rviz.png')
    launch = PrivateMasterLaunch(launch_for(args.n, args.gui, markers=True),
                                 os.path.join(args.out, 'roslaunch.log'))
    recorder = BagRecorder(bag_path, convoy_topics(args.n), os.path.join(args.out, 'rosbag.log'))
    wall_start = time.monotonic()
    try:
        launch.start()
        recorder.start()
        print('convoy_demo: %d robots, master %s, recording %.0f s to %s'
              % (args.n, launch.master_uri, args.duration, bag_path), flush=True)
        init_node('convoy_demo', anonymous=True, disable_signals=True)
        master = rosgraph.Master(rospy.get_name())
        alive = running(launch, recorder)
        poses = ['/robot%d/pose' % i for i in range(1, args.n + 1)]
        wait_for(lambda: recorder.receiving(master, poses), STARTUP_TIMEOUT_S,
                 'the poses of robot1..robot%d, recorded' % args.n, POLL_S, alive=alive)
        t0 = time.monotonic()
        wait_for(lambda: time.monotonic() - t0 >= args.duration, args.duration + 5.0,
                 'the end of the run', POLL_S, alive=alive)
        if recorder.stop() != 0:
            raise HarnessError('rosbag record did not close %s (see %s)'
                               % (bag_path, recorder.log_path))
        saved, image_error = save_canvas(canvas_png)
        rviz_saved, rviz_error = save_rviz(rviz_png, args.n)
    except (HarnessError, WaitError, rospy.ROSException) as err:
        # wait_for blames no process for an exit: name the recorder when it was it.
        failed, reason = launch, err
        if recorder.exited():
            failed, reason = recorder, 'rosbag record exited before the end of the run'
        print('convoy_demo: FAILED: %s\nlast lines of %s:\n%s'
              % (reason, failed.log_path, failed.tail()), file=sys.stderr)
        return 1
    finally:
        rospy.signal_shutdown('convoy_demo finished')
        recorder.stop()
        code = launch.stop()
    if code not in (0, None):
        print('convoy_demo: note: roslaunch exited with code %s (see %s)'
              % (code, launch.log_path), file=sys.stderr)

    # The table and figures come from the bag, through bag_report's code: anyone can remake
    # them from the bag alone (rosrun convoy bag_report convoy.bag).
    try:
        report = summarise_bag(bag_path)
    except BagError as err:
        print('convoy_demo: FAILED: %s' % err, file=sys.stderr)
        return 1
    trails_png, gaps_png = write_figures(report, args.out, 'convoy')
    print('\n' + '\n'.join(table_lines(report)))
    print('\nbag:    %s\ntrails: %s\ngaps:   %s\ncanvas: %s\nrviz:   %s\nlogs:   %s\n'
          'wall time: %.1f s'
          % (bag_path, trails_png, gaps_png, saved or '(not written)',
             rviz_saved or '(not written)', launch.log_path,
             time.monotonic() - wall_start))
    if image_error:
        print('convoy_demo: FAILED: could not save the canvas through /turtlesim/save_image: %s'
              % image_error, file=sys.stderr)
        return 1
    if rviz_error:
        print('convoy_demo: FAILED: could not take the rviz picture: %s' % rviz_error,
              file=sys.stderr)
        return 1
    return 0


def main():
    """Entry point of convoy_demo."""
    demo_main('convoy_demo', parse_args, run)
