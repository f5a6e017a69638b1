#!/usr/bin/env python3
"""Benchmark of the convoy with the autopilot leader, for 3 and 10 robots (./ws bench convoy_bench).

Per follower: mean and max distance to its leader and the fraction of time within the course's
tolerance + 0.5 m; follower pose -> command latency (median, p99); CPU and RSS of its
convoy_node. Per run: time from starting roslaunch until every follower has moved.

Each run happens in a child process of this script (rospy joins one master per process), with
its own master on a free port. Latency is measured two ways during the run:
- probe (the headline figure): an extra convoy_node whose poses come from this script at the
  pose rate; each follower pose has a unique x, which the command's linear.x = 0.3 * (xL - xF)
  gives back, so every command is matched to the pose it answers: latency = command received
  - pose sent (two TCPROS hops and this script's own overhead included: an upper bound);
- observed (per follower of the convoy): command received - that follower's newest pose
  received, both as `rosbag record` received them (the run's bag). Its p99 is inflated when a
  command overtakes its pose on the way to the recorder (then it pairs with the previous pose,
  16 ms earlier), so only its median is shown.
The gap figures are bag_report's on the same bag (the bag's path is printed at the end).
"""
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client

RUNS = ((3, 40.0), (10, 45.0))  # (robots, seconds recorded): the 10-robot tail starts late
TOLERANCE_M = 1.5
WITHIN_M = TOLERANCE_M + 0.5
STARTUP_TIMEOUT_S = 40.0
CHILD_TIMEOUT_S = 150.0
PROBE_PERIOD_S = 0.016  # turtlesim's pose period
PROBE_LEADER_X_M = 100.0  # far ahead on +x: the probe's command is linear.x = 0.3 * (100 - xF)
PROBE_STEP_M = 0.001  # follower x of probe pose k is k * PROBE_STEP_M (k < PROBE_POSES)
PROBE_POSES = 20000


class LatencyProbe:
    """Feeds an extra convoy_node poses at the pose rate and times each command it answers."""

    def __init__(self):
        import rospy
        from course_common.processes import spawn
        from geometry_msgs.msg import Twist
        from turtlesim.msg import Pose

        self._rospy, self._pose_type = rospy, Pose
        self._lock = threading.Lock()
        self._sent = {}
        self.latencies_s = []
        self.unmatched = 0
        self._leader = rospy.Publisher('/probe/leader_pose', Pose, queue_size=10)
        self._follower = rospy.Publisher('/probe/follower_pose', Pose, queue_size=10)
        self._sub = rospy.Subscriber('/probe/cmd_vel', Twist, self._on_cmd, queue_size=100)
        self._proc = spawn(
            ['rosrun', 'convoy', 'convoy_node', '__name:=convoy_probe',
             '_leader_pose:=/probe/leader_pose', '_follower_pose:=/probe/follower_pose',
             '_follower_speeds:=/probe/cmd_vel'], stop_timeout_s=20.0)
        self._stop = threading.Event()
        self._thread = None

    def connected(self):
        return (self._leader.get_num_connections() > 0
                and self._follower.get_num_connections() > 0
                and self._sub.get_num_connections() > 0)

    def _on_cmd(self, msg):
        now = time.monotonic()
        k = round((PROBE_LEADER_X_M - msg.linear.x / 0.3) / PROBE_STEP_M)
        with self._lock:
            sent = self._sent.pop(k, None)
            if sent is None:
                self.unmatched += 1
            else:
                self.latencies_s.append(now - sent)

    def _run(self):
        self._leader.publish(self._pose_type(x=PROBE_LEADER_X_M, y=0.0, theta=0.0))
        time.sleep(0.2)  # let the leader pose land before the first follower pose
        next_at = time.monotonic()
        for k in range(PROBE_POSES):
            if self._stop.is_set():
                break
            with self._lock:
                self._sent[k] = time.monotonic()
            self._follower.publish(self._pose_type(x=k * PROBE_STEP_M, y=0.0, theta=0.0))
            next_at += PROBE_PERIOD_S
            self._stop.wait(max(0.0, next_at - time.monotonic()))

    def start(self):
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def stop(self):
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        self._proc.stop()


def _proc_cpu_s(pid):
    """CPU seconds the process has used so far."""
    from course_common.processes import cpu_ticks
    return cpu_ticks(pid) / os.sysconf('SC_CLK_TCK')


def bag_timing(bag_path, n_robots):
    """Receipt times in the bag: {robot: pose times}, {robot: command times}, {robot: time of
    its first pose with a forward speed}."""
    import rosbag
    from convoy.recording import convoy_topics

    poses = {i: [] for i in range(1, n_robots + 1)}
    commands = {i: [] for i in range(1, n_robots + 1)}
    first_moving = {}
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, stamp in bag.read_messages(topics=convoy_topics(n_robots)):
            robot, kind = int(topic.split('/')[1][len('robot'):]), topic.split('/')[2]
            if kind == 'pose':
                poses[robot].append(stamp.to_sec())
                if msg.linear_velocity > 0.0:
                    first_moving.setdefault(robot, stamp.to_sec())
            else:
                commands[robot].append(stamp.to_sec())
    return ({r: sorted(t) for r, t in poses.items()}, {r: sorted(t) for r, t in commands.items()},
            first_moving)


def child(n_robots, duration_s):
    """One run; prints a JSON result on its last line."""
    import rosgraph
    import rosnode
    import rospy
    from convoy.bag_report import summarise_bag
    from convoy.harness import POLL_S, convoy_node_names, launch_for
    from convoy.metrics import delays_since_newest, percentile
    from convoy.recording import BagRecorder, convoy_topics
    from course_common.private_launch import PrivateMasterLaunch
    from course_common.processes import rss_mb
    from course_common.testing import wait_for

    out_dir = tempfile.mkdtemp(prefix='convoy_bench_')
    bag_path = os.path.join(out_dir, 'convoy.bag')
    launch = PrivateMasterLaunch(launch_for(n_robots), os.path.join(out_dir, 'roslaunch.log'))
    recorder = BagRecorder(bag_path, convoy_topics(n_robots), os.path.join(out_dir, 'rosbag.log'))
    try:
        launch.start()
        launch_wall_s = time.time() - (time.monotonic() - launch.started_at)  # the bag's clock
        recorder.start()
        rospy.init_node('convoy_bench', anonymous=True, disable_signals=True)
        master = rosgraph.Master('/convoy_bench')
        poses = ['/robot%d/pose' % i for i in range(1, n_robots + 1)]
        wait_for(lambda: recorder.receiving(master, poses), STARTUP_TIMEOUT_S, 'every robot',
                 POLL_S, alive=launch.alive)
        t0 = time.monotonic()  # the figures start here: the followers' catch-up counts
        names = convoy_node_names(n_robots)
        wait_for(lambda: set(names) <= set(rosnode.get_node_names()), STARTUP_TIMEOUT_S,
                 'the convoy nodes', POLL_S, alive=launch.alive)
        pids = {name: xmlrpc.client.ServerProxy(rosnode.get_api_uri(master, name))
                .getPid('/convoy_bench')[2] for name in names}
        probe = LatencyProbe()
        wait_for(probe.connected, STARTUP_TIMEOUT_S, 'the probe convoy_node', POLL_S,
                 alive=launch.alive)
        probe.start()
        cpu_t0 = time.monotonic()
        cpu0 = {name: _proc_cpu_s(pid) for name, pid in pids.items()}
        wait_for(lambda: time.monotonic() - t0 >= duration_s, duration_s + 30.0, 'the run', POLL_S,
                 alive=launch.alive)
        wall = time.monotonic() - cpu_t0
        cpu = {name: 100.0 * (_proc_cpu_s(pid) - cpu0[name]) / wall for name, pid in pids.items()}
        rss = {name: rss_mb(pid) for name, pid in pids.items()}
        recorder.stop()
        probe.stop()
    finally:
        rospy.signal_shutdown('bench run done')
        recorder.stop()
        launch.stop()
    # Gaps exactly as bag_report computes them; timings from the same bag's receipt times.
    report = summarise_bag(bag_path, within_m=WITHIN_M)
    pose_times, command_times, first_moving = bag_timing(bag_path, n_robots)
    moving = [first_moving.get(r) for r in range(2, n_robots + 1)]
    rows = []
    for pair, name in zip(report.pairs, names, strict=True):
        robot = int(pair.follower[len('robot'):])
        lat = delays_since_newest(pose_times[robot],
                                  [t for t in command_times[robot] if t >= report.start_s])
        rows.append({'follower': robot, 'node': name, 'mean_gap_m': pair.stats.mean_gap_m,
                     'max_gap_m': pair.stats.max_gap_m, 'within': pair.stats.within_fraction,
                     'lat_median_ms': 1e3 * percentile(lat, 0.5) if lat else None,
                     'lat_p99_ms': 1e3 * percentile(lat, 0.99) if lat else None,
                     'commands': len(lat), 'cpu_pct': cpu[name], 'rss_mb': rss[name]})
    all_moving = (None if None in moving else max(moving) - launch_wall_s)
    probe_lat = probe.latencies_s
    print(json.dumps({'n': n_robots, 'duration_s': duration_s, 'all_moving_s': all_moving,
                      'rows': rows, 'probe_commands': len(probe_lat),
                      'probe_unmatched': probe.unmatched,
                      'probe_median_ms': 1e3 * percentile(probe_lat, 0.5),
                      'probe_p99_ms': 1e3 * percentile(probe_lat, 0.99),
                      'bag': bag_path}))


def _fmt(value, pattern):
    return '-' if value is None else pattern % value


def main():
    if len(sys.argv) == 4 and sys.argv[1] == '--child':
        child(int(sys.argv[2]), float(sys.argv[3]))
        return 0
    results, started = [], time.monotonic()
    for n_robots, duration_s in RUNS:
        print('convoy_bench: %d robots, %.0f s with the autopilot leader...' % (n_robots,
                                                                                 duration_s),
              flush=True)
        proc = subprocess.run([sys.executable, os.path.abspath(__file__), '--child',
                               str(n_robots), str(duration_s)], capture_output=True, text=True,
                              timeout=CHILD_TIMEOUT_S)
        lines = proc.stdout.strip().splitlines()
        if proc.returncode != 0 or not lines or not lines[-1].startswith('{'):
            print('convoy_bench: the %d-robot run failed (exit %d):\n%s\n%s'
                  % (n_robots, proc.returncode, proc.stdout[-2000:], proc.stderr[-2000:]),
                  file=sys.stderr)
            return 1
        results.append(json.loads(lines[-1]))
    print('\n| N | follower | mean gap (m) | max gap (m) | within %.1f m | convoy_node CPU (%%) '
          '| RSS (MB) | observed latency median (ms) |' % WITHIN_M)
    print('|---|---|---|---|---|---|---|---|')
    for result in results:
        for row in result['rows']:
            print('| %d | robot%d | %.2f | %.2f | %.0f %% | %.1f | %.1f | %s |'
                  % (result['n'], row['follower'], row['mean_gap_m'], row['max_gap_m'],
                     100.0 * row['within'], row['cpu_pct'], row['rss_mb'],
                     _fmt(row['lat_median_ms'], '%.2f')))
    print('\n| N | recorded (s) | roslaunch -> every follower moving (s) | pose -> command '
          'latency median (ms) | p99 (ms) | probe commands (unmatched) |')
    print('|---|---|---|---|---|---|')
    for result in results:
        print('| %d | %.0f | %s | %.2f | %.2f | %d (%d) |'
              % (result['n'], result['duration_s'], _fmt(result['all_moving_s'], '%.1f'),
                 result['probe_median_ms'], result['probe_p99_ms'], result['probe_commands'],
                 result['probe_unmatched']))
    print('\nbags (rosrun convoy bag_report BAG remakes the gap figures): %s'
          % ' '.join(result['bag'] for result in results))
    print('\nconvoy_bench: done in %.0f s' % (time.monotonic() - started))
    return 0


if __name__ == '__main__':
    sys.exit(main())
