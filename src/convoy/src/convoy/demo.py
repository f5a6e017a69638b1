"""convoy_demo: the workspace's main demo, the convoy with its autopilot leader, headless.

rosrun convoy convoy_demo --out DIR [--duration S] [--n N] [--gui]
Starts the convoy launch file (convoy.launch for 3 robots, convoy_chain.launch otherwise) with
its own master on a free port, records every robot for a fixed time, saves the simulator's
canvas and a plot of each follower's gap to its leader, prints a summary and stops everything.
"""
import argparse
import os
import sys
import time

import rospy
from turtle_lite.srv import SaveImage

from convoy.control import DEFAULT_TOLERANCE_M
from convoy.harness import ConvoyRecorder, HarnessError, LaunchedConvoy, launch_for, wait_until
from convoy.metrics import follower_stats, gap_series

DEFAULT_DURATION_S = 30.0  # with start-up and shutdown, one demo stays well under a minute
MAX_DURATION_S = 600.0
STARTUP_TIMEOUT_S = 30.0  # a loaded 2-core machine can take ~10 s to bring up 13 processes
SERVICE_TIMEOUT_S = 10.0
# "Caught up": within the course's tolerance plus half a metre of the leader.
CATCH_UP_MARGIN_M = 0.5


def parse_args(argv):
    """Parses and checks the command line (argparse exits 2 with a message on bad input)."""
    parser = argparse.ArgumentParser(
        prog='convoy_demo', description='Run the convoy with its autopilot leader, headless, '
        'and write a picture of the trails and a plot of the gaps.')
    parser.add_argument('--out', required=True, help='directory for the PNGs and logs')
    parser.add_argument('--duration', type=float, default=DEFAULT_DURATION_S,
                        help='seconds to record once every robot is up (default %(default)s)')
    parser.add_argument('--n', type=int, default=3,
                        help='robots in the convoy, leader included, 2..10 (default 3: the '
                        "course's convoy.launch)")
    parser.add_argument('--gui', action='store_true', help="open the simulator's window")
    args = parser.parse_args(argv)
    if not 2 <= args.n <= 10:
        parser.error('--n must be an integer from 2 to 10, got %d' % args.n)
    if not 1.0 <= args.duration <= MAX_DURATION_S:
        parser.error('--duration must be between 1 and %g s, got %g'
                     % (MAX_DURATION_S, args.duration))
    args.out = os.path.abspath(args.out)
    return args


def plot_gaps(path, series, tolerance_m, threshold_m):
    """Writes a PNG of each follower's gap to its leader over time."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt  # after choosing the headless backend

    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    for robot, points in sorted(series.items()):
        ax.plot([t for t, _ in points], [g for _, g in points],
                label='robot%d to robot%d' % (robot, robot - 1), linewidth=1.2)
    ax.axhline(tolerance_m, color='grey', linestyle='--', linewidth=1,
               label='tolerance %.1f m' % tolerance_m)
    ax.axhline(threshold_m, color='grey', linestyle=':', linewidth=1,
               label='caught up %.1f m' % threshold_m)
    ax.set_xlabel('time since every robot was up (s)')
    ax.set_ylabel('distance to its leader (m)')
    ax.set_title('Convoy: each follower chasing its leader')
    ax.grid(True, alpha=0.3)
    ax.legend(loc='upper right', fontsize='small')
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def save_canvas(path):
    """Asks the simulator for a PNG of its canvas; returns (path written, None) or (None, error)."""
    try:
        rospy.wait_for_service('/turtlesim/save_image', SERVICE_TIMEOUT_S)
        return rospy.ServiceProxy('/turtlesim/save_image', SaveImage)(path).path, None
    except (rospy.ROSException, rospy.ServiceException) as err:
        return None, str(err)


def run(args):
    """Runs the demo; returns the process exit code."""
    os.makedirs(args.out, exist_ok=True)
    trails_png = os.path.join(args.out, 'convoy_trails.png')
    gaps_png = os.path.join(args.out, 'convoy_gaps.png')
    launch = LaunchedConvoy(launch_for(args.n, args.gui), os.path.join(args.out, 'roslaunch.log'))
    threshold_m = DEFAULT_TOLERANCE_M + CATCH_UP_MARGIN_M
    wall_start = time.monotonic()
    try:
        launch.start()
        print('convoy_demo: %d robots, master %s, recording %.0f s'
              % (args.n, launch.master_uri, args.duration), flush=True)
        rospy.init_node('convoy_demo', anonymous=True, disable_signals=True)
        recorder = ConvoyRecorder(args.n)
        wait_until(recorder.all_seen, STARTUP_TIMEOUT_S,
                   'the poses of robot1..robot%d' % args.n, launch.alive)
        recorder.start_recording()
        t0 = time.monotonic()
        wait_until(lambda: time.monotonic() - t0 >= args.duration, args.duration + 5.0,
                   'the end of the run', launch.alive)
        recorder.stop_recording()
        recorder.close()
        saved, image_error = save_canvas(trails_png)
    except (HarnessError, rospy.ROSException) as err:
        print('convoy_demo: FAILED: %s\nlast lines of %s:\n%s'
              % (err, launch.log_path, launch.log_tail()), file=sys.stderr)
        return 1
    finally:
        rospy.signal_shutdown('convoy_demo finished')
        code = launch.stop()
    if code not in (0, None):
        print('convoy_demo: note: roslaunch exited with code %s (see %s)'
              % (code, launch.log_path), file=sys.stderr)

    series, lines = {}, []
    for robot in range(2, args.n + 1):
        leader, follower = recorder.poses[robot - 1], recorder.poses[robot]
        series[robot] = [(t - t0, g) for t, g in gap_series(leader, follower)]
        stats = follower_stats(leader, follower, threshold_m, t_origin_s=t0)
        catch_up = ('%.1f s' % stats.catch_up_s if stats.catch_up_s is not None
                    else 'never (within %.0f s)' % args.duration)
        lines.append('| robot%d -> robot%d | %.2f | %.2f | %.0f %% | %s |'
                     % (robot, robot - 1, stats.mean_gap_m, stats.max_gap_m,
                        100.0 * stats.within_fraction, catch_up))
    plot_gaps(gaps_png, series, DEFAULT_TOLERANCE_M, threshold_m)
    print('\n| follower | mean gap (m) | max gap (m) | within %.1f m | catch-up |' % threshold_m)
    print('|---|---|---|---|---|')
    print('\n'.join(lines))
    print('\ntrails: %s\ngaps:   %s\nlogs:   %s\nwall time: %.1f s'
          % (saved or '(not written)', gaps_png, launch.log_path, time.monotonic() - wall_start))
    if image_error:
        print('convoy_demo: FAILED: could not save the canvas through /turtlesim/save_image: %s'
              % image_error, file=sys.stderr)
        return 1
    return 0


def main():
    """Entry point of convoy_demo."""
    args = parse_args(sys.argv[1:])
    try:
        sys.exit(run(args))
    except KeyboardInterrupt:
        print('convoy_demo: interrupted', file=sys.stderr)
        sys.exit(130)
