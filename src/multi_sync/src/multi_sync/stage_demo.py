"""stage_demo: the synchronisation lesson on the workspace's Stage, headless, in one command.

rosrun multi_sync stage_demo --out DIR [--speed MPS]
Starts `roslaunch multi_sync multi_sync.launch monitor:=true` on its own master (a free port)
without a display (stageros then runs headless), waits until every robot has moved after the
monitor's GO and stopped, saves stageros's picture of the world through /stage/save_image
(floor plan, robots, laser beams, trails), prints what each robot did (distance driven, where
it stopped and why, in its own log line), and stops everything as Ctrl-C would.
"""
import math
import os
import sys
import threading
import time

import rospy
from course_common.demo_cli import bounded, demo_main, demo_parser
from course_common.private_launch import POLL_S, PrivateMasterLaunch
from course_common.processes import rospy_texts
from course_common.startup import init_node
from course_common.waiting import WaitError, wait_for
from course_msgs.srv import SaveImage
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from multi_sync.lesson_report import Track, monitor_lines, stop_reasons, summary_lines

ROBOTS = 4  # the lesson's world: robot_0..robot_3
DEFAULT_SPEED_MPS = 0.2  # the lesson's
MIN_SPEED_MPS, MAX_SPEED_MPS = 0.05, 1.0
START_TIMEOUT_S = 60.0  # stageros and four robots up, ready, and the monitor's GO
# The longest course: the back pair drives about 3.4 m when nothing stops it before the
# leaders' backs; the margin covers a simulator slowed down by a loaded machine.
LONGEST_DRIVE_M = 4.0
DRIVE_MARGIN_S = 60.0
SERVICE_TIMEOUT_S = 10.0


def parse_args(argv):
    """Parses and checks the command line (argparse exits 2 with its message on bad input)."""
    parser = demo_parser('stage_demo', "Run the synchronisation lesson on the workspace's "
                         'Stage, headless, and write a picture of the world after GO.',
                         'directory for the picture and the logs')
    parser.add_argument('--speed', type=bounded(float, MIN_SPEED_MPS, MAX_SPEED_MPS, 'm/s'),
                        default=DEFAULT_SPEED_MPS,
                        help="the robots' speed, m/s (default %(default)s: the lesson's)")
    return parser.parse_args(argv)


class TeamTracks:
    """Every robot's Track, from /robot_N/base_pose_ground_truth and /robot_N/cmd_vel."""

    def __init__(self, n):
        self._lock = threading.Lock()
        self.tracks = [Track() for _ in range(n)]
        self._subs = []
        for i in range(n):
            self._subs.append(rospy.Subscriber('/robot_%d/base_pose_ground_truth' % i, Odometry,
                                               self._on_pose, i, queue_size=100))
            self._subs.append(rospy.Subscriber('/robot_%d/cmd_vel' % i, Twist, self._on_cmd, i,
                                               queue_size=100))

    def _on_pose(self, msg, i):
        p, v = msg.pose.pose.position, msg.twist.twist.linear
        with self._lock:
            self.tracks[i].on_pose(p.x, p.y, math.hypot(v.x, v.y))

    def _on_cmd(self, msg, i):
        with self._lock:
            self.tracks[i].on_command(msg.linear.x)

    def all(self, check):
        with self._lock:
            return all(check(track) for track in self.tracks)

    def summary(self, texts):
        """The printed summary of the run, with the lines it logged (lesson_report)."""
        with self._lock:
            return summary_lines(self.tracks, stop_reasons(texts, len(self.tracks)),
                                 monitor_lines(texts))


def save_world(path):
    """stageros's picture of the world; returns the path it wrote."""
    rospy.wait_for_service('/stage/save_image', SERVICE_TIMEOUT_S)
    return rospy.ServiceProxy('/stage/save_image', SaveImage)(path).path


def run(args):
    """Runs the demo; returns the process exit code."""
    os.makedirs(args.out, exist_ok=True)
    world_png = os.path.join(args.out, 'stage_world.png')
    launch_args = ['monitor:=true', 'pictures:=true']
    if args.speed != DEFAULT_SPEED_MPS:
        launch_args.append('speed_mps:=%g' % args.speed)
    # No DISPLAY: stageros runs headless (its WARN says so), as a demo on a server must.
    launch = PrivateMasterLaunch(['multi_sync', 'multi_sync.launch'] + launch_args,
                                 os.path.join(args.out, 'roslaunch.log'), env={'DISPLAY': None})
    wall_start = time.monotonic()
    try:
        launch.start()
        print('stage_demo: the synchronisation lesson on Stage, %d robots at %g m/s, master %s'
              % (ROBOTS, args.speed, launch.master_uri), flush=True)
        init_node('stage_demo', anonymous=True, disable_signals=True)
        team = TeamTracks(ROBOTS)
        wait_for(lambda: launch.printed('All robots GO!'), START_TIMEOUT_S,
                 "the monitor's GO", POLL_S, alive=launch.alive)
        drive_s = DRIVE_MARGIN_S + LONGEST_DRIVE_M / args.speed
        wait_for(lambda: team.all(Track.moved), drive_s, 'every robot to move after GO',
                 POLL_S, alive=launch.alive)
        wait_for(lambda: team.all(Track.stopped), drive_s, 'every robot to stop', POLL_S,
                 alive=launch.alive)
        saved = save_world(world_png)
        # The robots' and the monitor's lines as roslaunch printed them (output="screen").
        summary = team.summary(rospy_texts(launch.lines()))
    except (WaitError, rospy.ROSException, rospy.ServiceException) as err:
        print('stage_demo: FAILED: %s\nlast lines of %s:\n%s'
              % (err, launch.log_path, launch.tail()), file=sys.stderr)
        return 1
    finally:
        rospy.signal_shutdown('stage_demo finished')
        code = launch.stop()
    if code not in (0, None):
        print('stage_demo: note: roslaunch exited with code %s (see %s)'
              % (code, launch.log_path), file=sys.stderr)
    print('\n'.join(summary))
    print('\nworld:  %s\nlogs:   %s\nwall time: %.1f s'
          % (saved, launch.log_path, time.monotonic() - wall_start))
    return 0


def main():
    """Entry point of stage_demo."""
    demo_main('stage_demo', parse_args, run)
