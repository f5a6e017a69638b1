#!/usr/bin/env python3
"""Benchmark of multi_sync: start-up, how closely the robots start after GO, CPU and memory.

Run with `./ws bench multi_sync_bench`. Every run happens in a child process of this script
(rospy joins one master per process) with its own roscore on a free port, and a probe node
(this child) subscribed before roslaunch starts. Times are wall-clock times (time.time()) at
which the probe receives messages, whatever clock the nodes run on.

1. Teams on turtlesim (today's rows): for 4 and 20 robots, several runs of `roslaunch
   multi_sync multi_sync_turtlesim.launch team_size:=N monitor:=true`:
   * GO -> first non-zero cmd_vel per robot: "sent" is the robot's own clock when it
     published the command (its log line "first move command X ms after GO"), "seen" is
     when the probe received the command on robot_<i>/cmd_vel, from GO's (wall) stamp;
   * the resident memory (VmRSS) of each move_robot process;
   * the time from starting roslaunch to every robot having moved.
2. The lesson, 4 robots, on Stage (`roslaunch multi_sync multi_sync.launch`, no argument;
   DISPLAY unset, so stageros runs headless, at real time) and on turtlesim
   (`roslaunch multi_sync multi_sync_turtlesim.launch`, no argument), robots at 0.2 m/s:
   * roslaunch -> every robot's first sensor message (Stage: robot_<i>/base_scan;
     turtlesim: robot_<i>/pose) and -> every robot's ready status on team_status;
   * then WAIT_WINDOW_S with the robots waiting for the team, then `rosrun multi_sync monitor
     4` as the lesson starts it, then DRIVE_WINDOW_S from GO: CPU (utime + stime from /proc,
     in cores) of every process of the lesson: the simulator, the four robots, the monitor,
     and ROS's own (roscore, rosmaster, rosout, roslaunch), counted for both simulators;
     VmRSS of each at the end;
   * GO (when the probe receives it on team_status) -> each robot's first non-zero cmd_vel
     (when the probe receives it); the robots' own "first move command X ms after GO
     [arrived ...]" lines (on Stage the monitor stamps GO with sim time, so a robot measures
     from GO's arrival); GO -> the first pose of each robot that shows it moved (Stage:
     base_pose_ground_truth, published once per 100 ms step; turtlesim: pose, every 16 ms).
It prints markdown tables: medians over runs (and maxima).
"""
import json
import os
import re
import statistics
import sys
import threading
import time

import rospy
from course_common.processes import cpu_ticks, descendants, process_table, rss_mb, run_to_exit
from course_common.testing import WaitError, spawn, wait_for
from course_common.testing.master import Roscore
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from turtlesim.msg import Pose

from multi_sync.msg import RobotStatus

RUN_DEADLINE_S = 90.0  # a run step that has not happened by then is reported failed
CHILD_TIMEOUT_S = 180.0  # one whole run, start to stop, on a loaded machine
TEAM_RUNS = [(4, 5), (20, 3)]  # (team size, runs) on turtlesim
LESSON_RUNS = 3  # runs per simulator
LESSON_ROBOTS = 4
# CPU time comes in 10 ms ticks: 10 s windows resolve 0.001 of a core.
WAIT_WINDOW_S = 10.0  # robots ready, waiting for the team (no monitor yet)
DRIVE_WINDOW_S = 10.0  # from GO: on Stage the front pair reaches its stop after about 7 s
# simulator -> (launch file, (first-sensor topic, type), (pose topic, type))
LESSONS = {
    'Stage': ('multi_sync.launch', ('robot_%d/base_scan', LaserScan),
              ('robot_%d/base_pose_ground_truth', Odometry)),
    'turtlesim': ('multi_sync_turtlesim.launch', ('robot_%d/pose', Pose), ('robot_%d/pose', Pose)),
}
STEP_MS = {'Stage': 100, 'turtlesim': 16}  # how often each simulator publishes a pose
MOVED_M = 1e-6  # a pose this far from the start shows a move (one step moves 3-20 mm)
LOG_DIR = os.environ.get('TMPDIR', '/tmp')  # roslaunch's output of the latest run of each kind
FIRST_MOVE = re.compile(r'Robot (\d+): first move command ([0-9.]+) ms after GO')
RESULT = 'RESULT '  # a child's result line: RESULT <json>
CLK_TCK = os.sysconf('SC_CLK_TCK')


# --- what a run's child process does -------------------------------------------------------
class Probe:
    """What this process hears of a run, each event with the wall time it arrived here.

    Subscribed before roslaunch starts: team_status (ready statuses, GO) and every robot's
    cmd_vel; sensor topics (first message of each robot) and pose topics (the first pose
    that differs from the one before GO) on request.
    """

    def __init__(self, robots):
        self.lock = threading.Lock()
        self.robots = robots
        self.ready, self.moving, self.sensed, self.moved = {}, {}, {}, {}
        self.start_pose = {}  # robot id -> (x, y) of its first pose on the 'moved' topic
        self.go = self.go_stamp = None
        self.unconnected_at_go = []  # robots whose cmd_vel the probe was not connected to
        self._subs = {}
        self._status_sub = rospy.Subscriber('team_status', RobotStatus, self._on_status,
                                            queue_size=1000, tcp_nodelay=True)
        self._cmd_subs = [rospy.Subscriber('robot_%d/cmd_vel' % i, Twist, self._on_cmd, i,
                                           queue_size=10, tcp_nodelay=True)
                          for i in range(robots)]

    def _on_status(self, msg):
        now = time.time()
        with self.lock:
            if msg.header.frame_id == 'monitor':
                if self.go is None:
                    self.go, self.go_stamp = now, msg.header.stamp.to_sec()
                    self.unconnected_at_go = [i for i, sub in enumerate(self._cmd_subs)
                                              if sub.get_num_connections() == 0]
            elif msg.is_ready:
                self.ready.setdefault(msg.robot_id, now)

    def _on_cmd(self, msg, i):
        now = time.time()
        with self.lock:
            if msg.linear.x != 0.0:
                self.moving.setdefault(i, now)

    def subscribe(self, kind, topic, msg_type):
        """kind 'sensed': the first message of each robot; 'moved': the first pose after GO
        away from the first pose heard (before GO)."""
        self._subs[kind] = [rospy.Subscriber(topic % i, msg_type, self._on_message, (kind, i),
                                             queue_size=10)
                            for i in range(self.robots)]

    def unsubscribe(self, kind):
        for sub in self._subs.pop(kind, []):
            sub.unregister()

    def _on_message(self, msg, args):
        now = time.time()
        kind, i = args
        with self.lock:
            if kind == 'sensed':
                self.sensed.setdefault(i, now)
                return
            pose = getattr(msg, 'pose', None)
            x, y = (pose.pose.position.x, pose.pose.position.y) if pose else (msg.x, msg.y)
            start = self.start_pose.setdefault(i, (x, y))
            if (self.go is not None and i not in self.moved
                    and max(abs(x - start[0]), abs(y - start[1])) > MOVED_M):
                self.moved[i] = now

    def count(self, what):
        with self.lock:
            return len(getattr(self, what))

    def has_all(self, what):
        return self.count(what) >= self.robots


def first_move_lines(text):
    """robot id -> ms from the robots' "first move command X ms after GO" lines in text."""
    sent = {}
    for match in FIRST_MOVE.finditer(text):
        sent.setdefault(int(match.group(1)), float(match.group(2)))
    return sent


def lesson_processes(core, launch, monitor=None):
    """group -> pids of the lesson's processes: simulator, robots, monitor and ROS (roscore,
    rosmaster, rosout, roslaunch), found under the processes this run started."""
    table = process_table()

    def tree(root):
        return descendants(root, table)

    groups = {'simulator': [], 'robots': [], 'monitor': [], 'ROS': tree(core.pid)}
    groups['ROS'].append(launch.pid)
    for node in (pid for pid, (ppid, _) in table.items() if ppid == launch.pid):
        cmdline = table[node][1]  # a node's process, started by roslaunch
        group = ('robots' if 'move_robot' in cmdline else
                 'simulator' if 'stageros' in cmdline or 'turtlesim' in cmdline else 'ROS')
        groups[group].extend(tree(node))
    if monitor is not None:
        groups['monitor'] = tree(monitor.pid)
    return groups


def read_proc(read, pid):
    """read(pid) (cpu_ticks, rss_mb), or None if the process has ended."""
    try:
        return read(pid)
    except OSError:
        return None


def cpu_snapshot(groups):
    """(monotonic time, {pid: CPU ticks so far}) of every live pid in groups."""
    ticks = {pid: read_proc(cpu_ticks, pid) for pids in groups.values() for pid in pids}
    return time.monotonic(), {pid: t for pid, t in ticks.items() if t is not None}


def cores(groups, before, after):
    """group -> cores used between two snapshots (pids alive at both), and 'total'."""
    wall_s = after[0] - before[0]
    used = {name: sum(after[1][p] - before[1][p] for p in pids
                      if p in before[1] and p in after[1]) / CLK_TCK / wall_s
            for name, pids in groups.items()}
    used['total'] = sum(used.values())
    return used


def rss_by_group(groups):
    """group -> summed VmRSS (MB) of its processes, and 'total'."""
    sizes = {name: sum(read_proc(rss_mb, p) or 0.0 for p in pids)
             for name, pids in groups.items()}
    sizes['total'] = sum(sizes.values())
    return sizes


def start_core_and_probe(robots):
    core = Roscore().start()  # sets ROS_MASTER_URI here, for the probe and the children
    rospy.init_node('multi_sync_bench', anonymous=True, disable_signals=True)
    return core, Probe(robots)


def team_run(n):
    """One roslaunch of n turtlesim robots with the monitor; the result dict."""
    core, probe = start_core_and_probe(n)
    launch = None
    try:
        started = time.time()
        # The robots' screen output (nothing is lost on the way, unlike /rosout, whose
        # connections to new nodes may come up after their first lines).
        launch = spawn(['roslaunch', 'multi_sync', 'multi_sync_turtlesim.launch',
                        'team_size:=%d' % n, 'monitor:=true'],
                       log_path=os.path.join(LOG_DIR, 'multi_sync_bench_team%d.log' % n),
                       stop_timeout_s=30.0)
        wait_for(lambda: probe.go and probe.has_all('moving'), RUN_DEADLINE_S,
                 'every robot moving', 0.05, alive=launch.alive)
        groups = lesson_processes(core, launch)
        rss = [rss_mb(pid) for pid in groups['robots']]
        # The robots log their first-move line on their first tick after GO.
        wait_for(lambda: len(first_move_lines(launch.output())) >= n, RUN_DEADLINE_S,
                 'every first-move log line', 0.1, alive=launch.alive)
    finally:
        rospy.signal_shutdown('bench run done')
        if launch is not None:
            launch.stop()
        core.stop()
    return {'sent': list(first_move_lines(launch.output()).values()),
            'seen': [(t - probe.go_stamp) * 1e3 for t in probe.moving.values()],
            'rss': [r for r in rss if r is not None],
            'launch_s': max(probe.moving.values()) - started,
            'unconnected_at_go': probe.unconnected_at_go}


def lesson_run(simulator):
    """One run of the lesson's launch file, no argument, then the monitor; the result dict."""
    launch_file, sensor, pose = LESSONS[simulator]
    core, probe = start_core_and_probe(LESSON_ROBOTS)
    launch = monitor = None
    tag = simulator.lower()
    try:
        probe.subscribe('sensed', *sensor)
        started = time.time()
        launch = spawn(['roslaunch', 'multi_sync', launch_file], env={'DISPLAY': None},
                       log_path=os.path.join(LOG_DIR, 'multi_sync_bench_%s.log' % tag),
                       stop_timeout_s=30.0)
        wait_for(lambda: probe.has_all('sensed') and probe.has_all('ready'), RUN_DEADLINE_S,
                 "every robot's first sensor message and ready status", 0.02,
                 alive=launch.alive)
        probe.unsubscribe('sensed')  # 1081 beams x 4 robots x 10 Hz: not during the windows
        groups = lesson_processes(core, launch)
        before = cpu_snapshot(groups)
        time.sleep(WAIT_WINDOW_S)  # the measurement window, not a wait for something
        waiting = cores(groups, before, cpu_snapshot(groups))
        # The poses before GO, from connections made before the monitor starts.
        probe.subscribe('moved', *pose)
        wait_for(lambda: probe.has_all('start_pose'), RUN_DEADLINE_S,
                 "every robot's pose before GO", 0.02, alive=launch.alive)
        monitor = spawn(['rosrun', 'multi_sync', 'monitor', str(LESSON_ROBOTS)],
                        log_path=os.path.join(LOG_DIR, 'multi_sync_bench_%s_monitor.log' % tag),
                        stop_timeout_s=30.0)
        wait_for(lambda: probe.go, RUN_DEADLINE_S, 'GO on team_status', alive=monitor.alive)
        groups = lesson_processes(core, launch, monitor)
        before = cpu_snapshot(groups)
        wait_for(lambda: probe.has_all('moving') and probe.has_all('moved'), DRIVE_WINDOW_S,
                 'every robot moving', 0.05, alive=launch.alive)
        probe.unsubscribe('moved')
        time.sleep(max(0.0, before[0] + DRIVE_WINDOW_S - time.monotonic()))
        driving = cores(groups, before, cpu_snapshot(groups))
        rss = rss_by_group(groups)
        wait_for(lambda: len(first_move_lines(launch.output())) >= LESSON_ROBOTS,
                 RUN_DEADLINE_S, 'every first-move log line', 0.1, alive=launch.alive)
    finally:
        rospy.signal_shutdown('bench run done')
        for proc in (monitor, launch, core):
            if proc is not None:
                proc.stop()
    return {'sensed_s': max(probe.sensed.values()) - started,
            'ready_s': max(probe.ready.values()) - started,
            'go_cmd_ms': [(t - probe.go) * 1e3 for t in probe.moving.values()],
            'sent_ms': list(first_move_lines(launch.output()).values()),
            'moved_ms': [(t - probe.go) * 1e3 for t in probe.moved.values()],
            'cpu_waiting': waiting, 'cpu_driving': driving,
            'cpu_both': {g: (waiting[g] * WAIT_WINDOW_S + driving[g] * DRIVE_WINDOW_S)
                         / (WAIT_WINDOW_S + DRIVE_WINDOW_S) for g in driving},
            'rss': rss,
            'unconnected_at_go': probe.unconnected_at_go}


def child(argv):
    """`--run team N` or `--run lesson SIMULATOR`: one run; prints its RESULT line."""
    try:
        result = team_run(int(argv[1])) if argv[0] == 'team' else lesson_run(argv[1])
    except WaitError as err:
        print('bench: run failed: %s' % err, flush=True)
        return 1
    print(RESULT + json.dumps(result), flush=True)
    return 0


# --- the parent: runs, tables ----------------------------------------------------------------
def run(args, label):
    """One run in a child process: its result dict, or None (said why)."""
    try:
        code, output = run_to_exit([sys.executable, os.path.abspath(__file__), '--run', *args],
                                   CHILD_TIMEOUT_S)
    except WaitError as err:
        code, output = None, str(err)
    lines = output.splitlines()
    found = [line[len(RESULT):] for line in lines if line.startswith(RESULT)]
    result = json.loads(found[-1]) if code == 0 and found else None
    print('bench: %s: %s' % (label, 'ok' if result else 'FAILED'), flush=True)
    if result is None:
        print('\n'.join(lines[-15:]), flush=True)
    elif result['unconnected_at_go']:
        print('bench:   the probe was not yet connected to the cmd_vel of robot(s) %s at GO'
              % result['unconnected_at_go'], flush=True)
    return result


def median_max(values, fmt):
    return (fmt + ' / ' + fmt) % (statistics.median(values), max(values)) if values else '-'


def team_table(rows):
    print('| robots | runs ok | GO→first cmd sent, median / max (ms) '
          '| GO→first cmd seen, median / max (ms) | RSS per move_robot, median / max (MB) '
          '| roslaunch→all moving, median / max (s) |')
    print('|---:|---:|---:|---:|---:|---:|')
    for n, runs, results in rows:
        def every(key, results=results):
            return [v for res in results for v in res[key]]
        print('| %d | %d/%d | %s | %s | %s | %s |'
              % (n, len(results), runs, median_max(every('sent'), '%.1f'),
                 median_max(every('seen'), '%.1f'), median_max(every('rss'), '%.1f'),
                 median_max([res['launch_s'] for res in results], '%.1f')))
    print()
    print('Medians and maxima are over every robot of every run; target: max GO→first '
          'cmd under 20 ms at 20 robots.')


def lesson_table(lessons):
    names = list(lessons)
    print('| the lesson, 4 robots, roslaunch with no argument | %s |'
          % ' | '.join('%s: %s (%d/%d runs)' % (n, LESSONS[n][0], len(lessons[n]), LESSON_RUNS)
                       for n in names))
    print('|---|' + '---:|' * len(names))

    def row(label, cell):
        print('| %s | %s |' % (label, ' | '.join(cell(lessons[n], n) if lessons[n] else '-'
                                                   for n in names)))

    def per_run(key, fmt):  # a run's figure: the value, or the last robot's
        return lambda results, _n: median_max([max(res[key]) if isinstance(res[key], list)
                                                else res[key] for res in results], fmt)

    def every(key, fmt):
        return lambda results, _n: median_max([v for res in results for v in res[key]], fmt)

    def split(key, fmt):
        def cell(results, _n):
            median = {g: statistics.median(res[key][g] for res in results)
                      for g in results[0][key]}
            return (fmt + ' (' + ' / '.join([fmt] * 4) + ')') % (
                median['total'], median['simulator'], median['robots'], median['monitor'],
                median['ROS'])
        return cell

    row('roslaunch → every robot\'s first scan (Stage) / pose (turtlesim), s',
        per_run('sensed_s', '%.2f'))
    row('roslaunch → every robot\'s ready status on team_status, s', per_run('ready_s', '%.2f'))
    row('GO → last robot\'s first non-zero cmd_vel, both as the probe receives them, ms',
        per_run('go_cmd_ms', '%.1f'))
    row('GO → first move command, the robots\' log lines (all robots), ms',
        every('sent_ms', '%.1f'))
    row('GO → last robot\'s first pose showing it moved, ms (one pose per step: %s)'
        % ', '.join('%s %d ms' % (n, STEP_MS[n]) for n in names), per_run('moved_ms', '%.0f'))
    row('CPU, %.0f s waiting for the team, cores: total (simulator / robots / monitor / ROS)'
        % WAIT_WINDOW_S, split('cpu_waiting', '%.3f'))
    row('CPU, %.0f s from GO, cores: total (simulator / robots / monitor / ROS)'
        % DRIVE_WINDOW_S, split('cpu_driving', '%.3f'))
    row('CPU, both windows (%.0f s), cores: total (simulator / robots / monitor / ROS)'
        % (WAIT_WINDOW_S + DRIVE_WINDOW_S), split('cpu_both', '%.3f'))
    row('RSS at the end, MB: total (simulator / robots / monitor / ROS)', split('rss', '%.0f'))
    print()
    print('Median / maximum over runs (the log lines, 0.1 ms steps: over every robot of every '
          'run); CPU and RSS: the median of each group, and of the total. Times on the wall '
          'clock, as a probe receives the messages; target: GO → last robot moving under 20 ms '
          'on Stage. The monitor sends GO to the robots and the probe in one pass, in the order '
          'they connected, so a command can reach the probe before GO does. Stage runs '
          'headless at real time; the monitor and the robots started after it run on sim time '
          '(GO waits for the monitor\'s first /clock, so its stamp is sim time, not 0). '
          'ROS = roscore, rosmaster, rosout and roslaunch. The monitor is started by hand '
          '(rosrun) once every robot is ready, as in the lesson. Robots drive at 0.2 m/s on '
          'both; on Stage the bumper stops them after about 7 s, on turtlesim after 25 s.')


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == '--run':
        return child(sys.argv[2:])
    started = time.monotonic()
    teams = []
    for n, runs in TEAM_RUNS:
        results = [run(['team', str(n)], '%d robots on turtlesim, run %d' % (n, r + 1))
                   for r in range(runs)]
        teams.append((n, runs, [res for res in results if res]))
    lessons = {}
    for r in range(LESSON_RUNS):  # alternately, so that a change of load touches both
        for simulator in LESSONS:
            result = run(['lesson', simulator], 'the lesson on %s, run %d' % (simulator, r + 1))
            lessons.setdefault(simulator, [])
            if result:
                lessons[simulator].append(result)
    print()
    team_table(teams)
    print()
    lesson_table(lessons)
    print()
    print('bench: done in %.0f s' % (time.monotonic() - started))
    return 0


if __name__ == '__main__':
    sys.exit(main())
