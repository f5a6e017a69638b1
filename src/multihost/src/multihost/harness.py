"""Run a team's processes on the hosts of multihost.hosts and watch it (tests and bench).

Team starts commands inside host namespaces, each a course_common ChildProcess (a session of
its own, its log in a file), and stops them all at close (also at interpreter exit). Probe
reads the JSON events of a team_probe_node running on a host.
"""
import atexit
import json
import math
import os
import sys
import threading
import time

from course_common.processes import ChildProcess, run_to_exit

from multihost import hosts as hosts_mod

STOP_WAIT_S = 20.0  # roslaunch gives its nodes 15 s after SIGINT before escalating


class Team:
    """Processes on hosts, by name; close() stops every one (SIGINT, then SIGKILL)."""

    def __init__(self, hosts, log_dir):
        self.hosts = hosts
        self.log_dir = str(log_dir)
        self.procs = {}
        self.started_at = {}  # name: wall time just before its start (nothing of it is older)
        # ROS_HOME made here, before any process: roscore and the probe start together, and
        # roslaunch's pid file code fails (FileExistsError) if another makes it between its
        # exists() and its makedirs() (a loaded run saw roscore die so, the probe waiting 60 s).
        os.makedirs(self.ros_home(), exist_ok=True)
        atexit.register(self.close)

    def env(self, i, extra=None):
        """The environment of a process on host i, as changes to this process's (a value None
        removes a variable): what hosts.host_env gives, ROS_HOME in the log folder, extra."""
        env = hosts_mod.host_env(i)
        env['ROS_HOME'] = self.ros_home()
        env['PYTHONUNBUFFERED'] = '1'
        env.update(extra or {})
        return {**{k: None for k in os.environ if k not in env}, **env}

    def ros_home(self):
        return os.path.join(self.log_dir, 'ros_home')

    def start(self, name, i, command, extra_env=None, on_line=None):
        """Start command (argv list) on host i as `name`; env values None unset a variable.
        on_line: called with each line of its output (stdout and stderr)."""
        if name in self.procs:
            raise ValueError('a process named %s already runs' % name)
        self.started_at[name] = time.time()
        proc = ChildProcess(self.hosts.argv(i, command), env=self.env(i, extra_env),
                            log_path=self.log_path(name), stop_timeout_s=STOP_WAIT_S,
                            on_line=on_line).start()
        self.procs[name] = proc
        return proc

    def log_path(self, name):
        return os.path.join(self.log_dir, '%s.log' % name)

    def tail(self, name, lines=30):
        try:
            with open(self.log_path(name), encoding='utf-8', errors='replace') as f:
                return ''.join(f.readlines()[-lines:])
        except OSError:
            return ''

    def exited(self, names=None):
        """{name: exit status} of the processes (of names) that are no longer running."""
        return {n: p.returncode for n, p in self.procs.items()
                if (names is None or n in names) and p.exited()}

    def run(self, i, command, extra_env=None, timeout_s=30.0):
        """Run command on host i to completion; (status, output)."""
        return run_to_exit(self.hosts.argv(i, command), timeout_s, env=self.env(i, extra_env))

    def stop(self, names=None):
        """Stop the processes (all, or names): SIGINT to each session, SIGKILL after a while.

        Returns the names of those that had not ended STOP_WAIT_S after SIGINT (hung).
        """
        procs = [(n, p) for n, p in self.procs.items() if names is None or n in names]
        for _name, proc in procs:
            proc.interrupt()  # all at once: roslaunch takes seconds to stop its nodes
        deadline = time.monotonic() + STOP_WAIT_S
        hung = []
        for name, proc in procs:
            if proc.stop(max(0.1, deadline - time.monotonic())) is None:  # it was killed
                hung.append(name)
        for name, _proc in procs:
            del self.procs[name]
        return hung

    def close(self):
        self.stop()


class Probe:
    """The events of a team_probe_node (started on a host through Team.start), as they arrive."""

    def __init__(self, team, name, i, args):
        self._lock = threading.Lock()
        self._events = []
        self.name = name
        command = [sys.executable, '-m', 'multihost.team_probe_node', *args]
        self.proc = team.start(name, i, command, on_line=self._on_line)

    def _on_line(self, line):
        try:
            event = json.loads(line)
        except ValueError:
            return  # a log line of the node, not an event
        if isinstance(event, dict):
            with self._lock:
                self._events.append(event)

    def events(self, kind, robot=None, since=None):
        with self._lock:
            return [e for e in self._events if e['e'] == kind
                    and (robot is None or e.get('r') == robot)
                    and (since is None or e.get('t', 0.0) >= since)]

    def ready(self):
        return bool(self.events('ready'))

    def go_stamp(self):
        """The first GO's header stamp (when the monitor sent it), or None.

        Not when the probe received it: the monitor sends GO to its subscribers one after
        the other, so a robot may act on GO before the probe hears it.
        """
        gos = self.events('go')
        return gos[0]['stamp'] if gos else None

    def first_move(self, robot):
        """Receive time of robot's first non-zero command, or None."""
        moves = [e['t'] for e in self.events('cmd', robot) if e['v'] != 0.0]
        return moves[0] if moves else None

    def last_pose(self, robot):
        poses = self.events('pose', robot)
        return poses[-1] if poses else None

    def last_change(self, robot, eps_m=1e-4):
        """Receive time of the last pose that differed from the one before it, or None."""
        poses = self.events('pose', robot)
        for before, after in zip(reversed(poses[:-1]), reversed(poses[1:]), strict=True):
            if math.hypot(after['x'] - before['x'], after['y'] - before['y']) > eps_m:
                return after['t']
        return None

    def moving(self, robot, window_s=0.5):
        """True when robot's pose changed within the last window_s seconds."""
        changed = self.last_change(robot)
        return changed is not None and time.time() - changed < window_s

    def still(self, robot, window_s=0.5):
        """True when robot's poses keep coming (the last received within window_s) and did not
        change for window_s seconds. Poses that stopped coming prove nothing: the probe, or
        this process reading its lines, may be behind on a loaded machine."""
        last = self.last_pose(robot)
        return last is not None and time.time() - last['t'] < window_s \
            and not self.moving(robot, window_s)

    def stopped(self, robot, window_s=0.5):
        """still, and the simulator applies no speed: the robot stands because it was told to."""
        return self.still(robot, window_s) and self.last_pose(robot)['v'] == 0.0

    def stalled(self, robot, window_s=0.5):
        """still although the simulator applies a speed: pushing against something (Stage)."""
        return self.still(robot, window_s) and self.last_pose(robot)['v'] != 0.0

    def stalled_poses(self, robot, eps_m=1e-4):
        """The poses at which robot had not moved since the one before although the simulator
        applied a speed (meaningful with every pose printed, --pose-period 0)."""
        poses = self.events('pose', robot)
        return [after for before, after in zip(poses[:-1], poses[1:], strict=True)
                if after['v'] != 0.0
                and math.hypot(after['x'] - before['x'], after['y'] - before['y']) <= eps_m]

    def gap(self, leader, follower):
        """Distance between the latest poses of two robots, or None."""
        a, b = self.last_pose(leader), self.last_pose(follower)
        return None if a is None or b is None else math.hypot(a['x'] - b['x'], a['y'] - b['y'])

    def warnings(self, since=None):
        return [(e['node'], e['msg']) for e in self.events('log', since=since)]

