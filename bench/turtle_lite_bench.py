"""turtle_lite benchmark: the real turtlesim's measured scenarios, run against turtle_lite.

Run with `./ws bench turtle_lite_bench` (devel space sourced, /usr/bin/python3). It starts its
own roscore on a free port, starts and stops every simulator it measures, and prints a
markdown table with the real turtlesim's figures (measured on the same 2-core class of
machine), ours, and the ratio ours / turtlesim. Scenarios:

* pose rate and interval jitter of /turtle1/pose with 1, 10, 50 and 200 turtles, idle;
* CPU (% of one core, utime + stime from /proc/<pid>/stat over a fixed window) and RSS,
  idle and with every turtle moving (cmd_vel at 10 Hz each from one load process, one pose
  subscriber per turtle in this process);
* rosrun to the first /turtle1/pose (roscore already up), median of several starts, and
  the same with the executable started directly (what rosrun's own lookup costs);
* teleport_absolute round trip (persistent proxy) and spawn round trip (new connection);
* cmd_vel to the first pose that shows the commanded velocity;
* `rosnode kill` to process exit, and the exit code.

The load generator is this same file run with `--load NAME...` (internal use).
"""

import math
import os
import random
import statistics
import subprocess
import sys
import threading
import time

import rosnode
import rospy
from course_common.testing import WaitError, cpu_ticks, rss_mb, spawn, wait_for
from course_common.testing.master import Roscore
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose
from turtlesim.srv import Kill, Spawn, TeleportAbsolute

# CPU / rate measurement windows. CPU time comes in 10 ms clock ticks, so an idle figure
# near 1 % needs the longer window to resolve 0.1 %; the whole run stays near 2 minutes.
IDLE_WINDOW_S = 10.0
MOVING_WINDOW_S = 5.0
STARTS = 5  # rosrun-to-first-pose samples (each also gives one kill-to-exit sample)
ROUND_TRIPS = 40  # teleport / spawn / cmd_vel samples
TURTLE_COUNTS = (1, 10, 50, 200)
CMD_RATE_HZ = 10.0  # cmd_vel rate per moving turtle, as in the reference
MOVE_LINEAR_MPS = 1.0  # circles of radius 1 m: the turtles stay off the walls
MOVE_ANGULAR_RADPS = 1.0
START_DEADLINE_S = 30.0  # generous: the box is shared and may be loaded
CLK_TCK = os.sysconf("SC_CLK_TCK")

# The real turtlesim_node (Noetic, offscreen Qt), measured: the README's turtle_lite table.
REFERENCE = {
    "rate_1": 62.50, "rate_10": 62.50, "rate_50": 62.50,
    "cpu_idle_1": 0.65, "cpu_idle_10": 1.0, "cpu_idle_50": 1.75,
    "cpu_move_1": 4.3, "cpu_move_50": 17.8,
    "rss": 35.5,  # 34-37 MB offscreen
    "startup": 400.0, "teleport": 8.8, "spawn": 17.9, "cmd_vel": 11.7, "kill": 550.0,
}


def cpu_percent(pid, window_s):
    t0, c0 = time.monotonic(), cpu_ticks(pid)
    time.sleep(window_s)
    t1, c1 = time.monotonic(), cpu_ticks(pid)
    return 100.0 * (c1 - c0) / CLK_TCK / (t1 - t0)


def interval_stats(stamps):
    """(rate Hz, interval std ms, max interval ms) of a list of receive times."""
    if len(stamps) < 3:
        return math.nan, math.nan, math.nan
    gaps = [b - a for a, b in zip(stamps, stamps[1:], strict=False)]
    return ((len(stamps) - 1) / (stamps[-1] - stamps[0]), statistics.pstdev(gaps) * 1e3,
            max(gaps) * 1e3)


def run_load(names):
    """Load generator: Twist at CMD_RATE_HZ on <name>/cmd_vel for every name, one process."""
    rospy.init_node("bench_load", anonymous=True, disable_signals=True)
    pubs = [rospy.Publisher(f"{name}/cmd_vel", Twist, queue_size=1) for name in names]
    twist = Twist()
    twist.linear.x, twist.angular.z = MOVE_LINEAR_MPS, MOVE_ANGULAR_RADPS
    period = 1.0 / CMD_RATE_HZ
    next_t = time.monotonic()
    while not rospy.is_shutdown():
        for pub in pubs:
            pub.publish(twist)
        next_t += period
        time.sleep(max(0.0, next_t - time.monotonic()))


class Bench:
    """Owns the roscore, the bench node and whatever simulator is running."""

    sim_command = ("rosrun", "turtle_lite", "turtlesim_node")  # what "rosrun" measures

    def __init__(self):
        self.core = Roscore().start()  # sets ROS_MASTER_URI here, for us and our children
        self.env = dict(os.environ)
        self.sim = None
        self.results = {}
        self.notes = []
        self._lock = threading.Lock()
        self._stamps = []
        self._poses = []

        rospy.init_node("turtle_lite_bench", anonymous=True, disable_signals=True)
        self.pose_sub = rospy.Subscriber("turtle1/pose", Pose, self._on_pose, queue_size=100)

    # --- helpers -------------------------------------------------------------------------

    def _on_pose(self, msg):
        now = time.monotonic()
        with self._lock:
            self._stamps.append(now)
            self._poses.append((now, msg))

    def clear_poses(self):
        with self._lock:
            self._stamps = []
            self._poses = []

    def stamps(self):
        with self._lock:
            return list(self._stamps)

    def start_sim(self, command=None):
        """rosrun the simulator; return seconds until the first /turtle1/pose arrives."""
        self.clear_poses()
        t0 = time.monotonic()
        self.sim = spawn(list(command or self.sim_command))
        wait_for(lambda: self.stamps(), START_DEADLINE_S, "the first /turtle1/pose")
        return self.stamps()[0] - t0

    def kill_sim(self):
        """rosnode kill the simulator; return (seconds to exit, exit code)."""
        t0 = time.monotonic()
        rosnode.kill_nodes(["/turtlesim"])
        try:
            code = self.sim.wait_exit(START_DEADLINE_S)
        except WaitError:
            code = self.sim.stop()
            self.notes.append("the simulator did not exit on rosnode kill; stopped")
        elapsed = time.monotonic() - t0
        self.sim = None
        return elapsed, code

    def close(self):
        if self.sim is not None:
            self.sim.stop()
        rospy.signal_shutdown("bench done")
        self.core.stop()

    # --- scenarios -----------------------------------------------------------------------

    def startup_and_kill(self):
        # The executable rosrun ends up running, to split rosrun's own lookup time off.
        direct = subprocess.run(["catkin_find", "--first-only", "--libexec", "turtle_lite",
                                 "turtlesim_node"], env=self.env, capture_output=True,
                                text=True, check=True).stdout.strip()
        starts, direct_starts, kills, codes = [], [], [], []
        for _ in range(STARTS):
            for command, samples in ((None, starts), ([direct], direct_starts)):
                samples.append(self.start_sim(command) * 1e3)
                elapsed, code = self.kill_sim()
                kills.append(elapsed * 1e3)
                codes.append(code)
        self.results["startup"] = (statistics.median(starts), max(starts))
        self.results["startup_direct"] = (statistics.median(direct_starts), max(direct_starts))
        self.results["kill"] = (statistics.median(kills), max(kills))
        self.results["kill_codes"] = codes

    def round_trips(self):
        rospy.wait_for_service("turtle1/teleport_absolute", START_DEADLINE_S)
        teleport = rospy.ServiceProxy("turtle1/teleport_absolute", TeleportAbsolute,
                                      persistent=True)
        samples = []
        for i in range(ROUND_TRIPS):
            t0 = time.monotonic()
            teleport(5.0 + 0.01 * i, 5.0, 0.0)
            samples.append((time.monotonic() - t0) * 1e3)
        teleport.close()
        self.results["teleport"] = (statistics.median(samples), max(samples))

        samples, names = [], []
        for i in range(ROUND_TRIPS):
            spawn = rospy.ServiceProxy("spawn", Spawn)  # not persistent: a new connection
            t0 = time.monotonic()
            names.append(spawn(1.0 + 0.2 * i, 2.0, 0.0, "").name)
            samples.append((time.monotonic() - t0) * 1e3)
        self.results["spawn"] = (statistics.median(samples), max(samples))
        kill = rospy.ServiceProxy("kill", Kill, persistent=True)
        for name in names:
            kill(name)
        kill.close()

        pub = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
        wait_for(lambda: pub.get_num_connections() > 0, START_DEADLINE_S,
                   "the simulator to subscribe turtle1/cmd_vel")
        go, stop = Twist(), Twist()
        go.linear.x = 0.5
        samples = []
        for _ in range(ROUND_TRIPS):
            self.clear_poses()
            t0 = time.monotonic()
            pub.publish(go)
            wait_for(lambda: any(p.linear_velocity > 0 for _, p in self._poses_copy()),
                       START_DEADLINE_S, "a moving pose")
            first = next(t for t, p in self._poses_copy() if p.linear_velocity > 0)
            samples.append((first - t0) * 1e3)
            self.clear_poses()
            pub.publish(stop)
            wait_for(lambda: any(p.linear_velocity == 0 for _, p in self._poses_copy()),
                       START_DEADLINE_S, "a stopped pose")
            time.sleep(random.uniform(0.0, 0.016))  # decorrelate from the tick phase
        pub.unregister()
        self.results["cmd_vel"] = (statistics.median(samples), max(samples))

    def _poses_copy(self):
        with self._lock:
            return list(self._poses)

    def turtles(self, counts):
        spawn = rospy.ServiceProxy("spawn", Spawn, persistent=True)
        names = ["turtle1"]
        for n in counts:
            # Spread the turtles on a grid inside [2, 9] m so the 1 m circles miss the walls.
            while len(names) < n:
                k = len(names) - 1
                names.append(spawn(2.0 + (k % 15) * 0.5, 2.0 + (k // 15) * 0.5, 0.0, "").name)
            time.sleep(0.5)  # let the spawned turtles' first ticks pass before measuring
            self.clear_poses()
            idle_cpu = cpu_percent(self.sim.pid, IDLE_WINDOW_S)
            rate, std, gap = interval_stats(self.stamps())
            self.results[f"rate_{n}"] = (rate, std, gap)
            self.results[f"cpu_idle_{n}"] = idle_cpu
            self.results[f"rss_idle_{n}"] = rss_mb(self.sim.pid)
            self.moving(names)
        spawn.close()

    def moving(self, names):
        n = len(names)
        counts = [0] * n

        def counter(i):
            def on_msg(_msg):
                counts[i] += 1
            return on_msg

        # Raw (undeserialised) subscribers: the bench should not be the bottleneck.
        subs = [rospy.Subscriber(f"{name}/pose", rospy.AnyMsg, counter(i), queue_size=1)
                for i, name in enumerate(names)]
        load = spawn([sys.executable, __file__, "--load", *names], stop_timeout_s=10.0)
        try:
            wait_for(lambda: all(counts), START_DEADLINE_S,
                       f"poses from all {n} turtles")
            wait_for(lambda: any(p.linear_velocity > 0 for _, p in self._poses_copy()[-5:]),
                       START_DEADLINE_S, "turtle1 moving")
            time.sleep(0.5)
            before = list(counts)
            self.clear_poses()
            t0 = time.monotonic()
            own0 = cpu_ticks(os.getpid())
            cpu = cpu_percent(self.sim.pid, MOVING_WINDOW_S)
            elapsed = time.monotonic() - t0
            own = 100.0 * (cpu_ticks(os.getpid()) - own0) / CLK_TCK / elapsed
            rates = [(c - b) / elapsed for c, b in zip(counts, before, strict=True)]
            self.results[f"cpu_move_{n}"] = cpu
            self.results[f"bench_cpu_{n}"] = own
            self.results[f"rss_move_{n}"] = rss_mb(self.sim.pid)
            self.results[f"move_rate_{n}"] = (min(rates), interval_stats(self.stamps()))
        finally:
            load.stop()
            for sub in subs:
                sub.unregister()
        # Let the 1 s cmd_vel timeout stop everyone before the next idle window.
        time.sleep(1.2)

    # --- report --------------------------------------------------------------------------

    def table(self):
        r = self.results
        rows = []

        def row(label, key, ours, unit, digits=1):
            ref = REFERENCE.get(key)
            ratio = f"{ours / ref:.2f}" if ref and ours == ours else "—"
            ref_s = f"{ref:.{digits}f}" if ref is not None else "—"
            rows.append(f"| {label} | {ref_s} | {ours:.{digits}f} | {ratio} | {unit} |")

        for n in TURTLE_COUNTS:
            if f"rate_{n}" in r:
                rate, std, gap = r[f"rate_{n}"]
                row(f"/turtle1/pose rate, {n} idle (std {std:.2f} ms, max gap {gap:.1f} ms)",
                    f"rate_{n}", rate, "Hz", 2)
        for n in TURTLE_COUNTS:
            if f"move_rate_{n}" in r:
                low, (rate, std, gap) = r[f"move_rate_{n}"]
                rows.append(f"| pose rate, {n} moving: turtle1 (std {std:.2f} ms, max gap "
                            f"{gap:.1f} ms) / slowest turtle | 62.50 | {rate:.2f} / {low:.2f} "
                            f"| {rate / 62.5:.2f} | Hz |")
        for n in TURTLE_COUNTS:
            if f"cpu_idle_{n}" in r:
                row(f"CPU idle, {n} turtles", f"cpu_idle_{n}", r[f"cpu_idle_{n}"], "% core")
        for n in TURTLE_COUNTS:
            if f"cpu_move_{n}" in r:
                row(f"CPU, {n} turtles moving (bench process itself: "
                    f"{r[f'bench_cpu_{n}']:.0f} %)", f"cpu_move_{n}", r[f"cpu_move_{n}"],
                    "% core")
        for n in TURTLE_COUNTS:
            for state in ("idle", "move"):
                if f"rss_{state}_{n}" in r:
                    row(f"RSS, {n} turtles {'moving' if state == 'move' else 'idle'}", "rss",
                        r[f"rss_{state}_{n}"], "MB")
        labels = {
            "startup": "rosrun to first /turtle1/pose (median; max {:.0f} ms)",
            "startup_direct": "same, executable started directly (median; max {:.0f} ms)",
            "teleport": "teleport_absolute round trip, persistent (median; max {:.2f} ms)",
            "spawn": "spawn round trip, new connection (median; max {:.1f} ms)",
            "cmd_vel": "cmd_vel to first moving pose (median; max {:.1f} ms)",
            "kill": "rosnode kill to exit (median; max {:.0f} ms)",
        }
        for key, label in labels.items():
            if key in r:
                median, worst = r[key]
                row(label.format(worst), key, median, "ms", 2)
        out = ["| quantity | turtlesim | turtle_lite | ratio | unit |",
               "|---|---|---|---|---|", *rows]
        if "kill_codes" in r:
            out.append("")
            out.append(f"rosnode kill exit codes: {r['kill_codes']} (turtlesim: 0)")
        out.append(f"Windows: {IDLE_WINDOW_S:.0f} s idle, {MOVING_WINDOW_S:.0f} s moving per "
                   f"CPU/rate figure, {STARTS} starts, "
                   f"{ROUND_TRIPS} round trips each; CPU = utime+stime of the simulator "
                   "process over the window. Targets: 62.5 Hz up to 200 turtles, CPU <= "
                   "turtlesim, RSS < 60 MB, round trips < 20 ms.")
        out.append("Moving: every turtle gets cmd_vel at 10 Hz from one load process and has "
                   "one raw pose subscriber in the bench process, which itself needs CPU "
                   "(62.5 x N messages/s) on the same cores.")
        out.extend(self.notes)
        return "\n".join(out)


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--load":
        run_load(sys.argv[2:])
        return
    bench = Bench()
    failed = False
    try:
        print("bench: start-up / kill", flush=True)
        bench.startup_and_kill()
        bench.start_sim()
        print("bench: round trips", flush=True)
        bench.round_trips()
        print("bench: turtles idle and moving", flush=True)
        bench.turtles(TURTLE_COUNTS)
    except Exception as err:  # report what was measured before the failure
        failed = True
        print(f"bench: FAILED: {err!r}", file=sys.stderr)
    finally:
        bench.close()
    print(bench.table())
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
