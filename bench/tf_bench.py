"""tf benchmark: the cost of putting 50 turtles in tf, one broadcaster for all or one per turtle.

Run with `./ws bench tf_bench` (devel space sourced, /usr/bin/python3). It starts its own roscore
on a free port and one turtle_lite simulator with 50 turtles (each publishes its pose at
62.5 Hz, moving or not), then, one scenario at a time:

* one `pose_to_tf` for all, batched: every turtle's newest transform in one /tf message per
  16 ms tick (the default, ~rate_hz 62.5);
* one `pose_to_tf` for all, one /tf message per pose (~rate_hz 0, the tf2 tutorial's way);
* one `pose_to_tf` per turtle (`_turtles:=[turtleN] _rate_hz:=0`), the tf2 tutorial's
  turtle_tf2_broadcaster started once per turtle.

For each it measures, over a fixed window once every broadcaster follows its turtles: the
broadcasters' CPU (% of one core, utime + stime from /proc/<pid>/stat, summed), their RSS
(summed), and the /tf messages and transforms per second a listener in this process receives.
"""

import os
import socket
import subprocess
import sys
import time

import rosgraph
import rospy
from course_common.testing import wait_for
from tf2_msgs.msg import TFMessage
from turtlesim.srv import Spawn

TURTLES = 50
WINDOW_S = 10.0  # CPU time comes in 10 ms ticks: 10 s resolves 0.1 % of a core
START_DEADLINE_S = 180.0  # 50 Python processes starting on a shared 2-core machine
CLK_TCK = os.sysconf('SC_CLK_TCK')


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def cpu_ticks(pid):
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return int(fields[11]) + int(fields[12])  # utime, stime


def rss_mb(pid):
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return 0.0


def python_pid(proc):
    """rosrun runs the node as a child of bash: the node is the newest descendant process."""
    children = subprocess.run(['pgrep', '-P', str(proc.pid)], capture_output=True, text=True)
    pids = [int(p) for p in children.stdout.split()]
    return pids[-1] if pids else proc.pid


class TfCounter:
    def __init__(self):
        self.messages = 0
        self.transforms = 0
        self.sub = rospy.Subscriber('/tf', TFMessage, self._on_tf, queue_size=100)

    def _on_tf(self, msg):
        self.messages += 1
        self.transforms += len(msg.transforms)


def subscribed_pose_topics(master):
    _pubs, subs, _srvs = master.getSystemState()
    return {t for t, nodes in subs for n in nodes
            if t.endswith('/pose') and n.startswith('/tfb_')}


def scenario(master, counter, label, commands):
    procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
             for c in commands]
    try:
        wait_for(lambda: len(subscribed_pose_topics(master)) == TURTLES, START_DEADLINE_S,
                   '%s following all %d turtles' % (label, TURTLES))
        time.sleep(2.0)  # let the connections settle before the window
        pids = [python_pid(p) for p in procs]
        ticks0 = sum(cpu_ticks(p) for p in pids)
        msgs0, tfs0 = counter.messages, counter.transforms
        t0 = time.monotonic()
        time.sleep(WINDOW_S)
        elapsed = time.monotonic() - t0
        cpu = 100.0 * (sum(cpu_ticks(p) for p in pids) - ticks0) / CLK_TCK / elapsed
        rss = sum(rss_mb(p) for p in pids)
        return (label, len(pids), cpu, rss, (counter.messages - msgs0) / elapsed,
                (counter.transforms - tfs0) / elapsed)
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                p.kill()
        wait_for(lambda: not subscribed_pose_topics(master), START_DEADLINE_S,
                   'the broadcasters of %s gone' % label)


def main():
    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    core = subprocess.Popen(['roscore', '-p', str(port)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    sim = None
    try:
        master = rosgraph.Master('/tf_bench')
        wait_for(lambda: _master_up(master), 30.0, 'roscore')
        sim = subprocess.Popen(['rosrun', 'turtlesim', 'turtlesim_node'],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rospy.init_node('tf_bench', disable_signals=True)
        rospy.wait_for_service('/spawn', 60.0)
        spawn = rospy.ServiceProxy('/spawn', Spawn)
        for i in range(2, TURTLES + 1):
            spawn(1.0 + (i % 8) * 1.2, 1.0 + (i // 8) * 1.2, 0.0, 'turtle%d' % i)
        counter = TfCounter()
        rosrun = ['rosrun', 'turtle_lite', 'pose_to_tf']
        rows = [
            scenario(master, counter, 'one pose_to_tf, batched (62.5 Hz)',
                     [rosrun + ['__name:=tfb_all']]),
            scenario(master, counter, 'one pose_to_tf, one message per pose',
                     [rosrun + ['__name:=tfb_all', '_rate_hz:=0']]),
            scenario(master, counter, 'one pose_to_tf per turtle',
                     [rosrun + ['__name:=tfb_%d' % i, '_turtles:=[turtle%d]' % i,
                                '_rate_hz:=0'] for i in range(1, TURTLES + 1)]),
        ]
        print('\n%d turtles, pose at 62.5 Hz each, %.0f s windows\n' % (TURTLES, WINDOW_S))
        print('| broadcaster | processes | CPU (% of one core) | RSS | /tf messages/s '
              '| transforms/s |')
        print('|---|---:|---:|---:|---:|---:|')
        for label, n, cpu, rss, msgs, tfs in rows:
            print('| %s | %d | %.1f %% | %.0f MB | %.0f | %.0f |' % (label, n, cpu, rss, msgs, tfs))
    finally:
        rospy.signal_shutdown('tf_bench done')
        for proc in (sim, core):
            if proc is not None:
                proc.terminate()
                try:
                    proc.wait(20)
                except subprocess.TimeoutExpired:
                    proc.kill()


def _master_up(master):
    try:
        master.getPid()
        return True
    except OSError:
        return False


if __name__ == '__main__':
    sys.exit(main())
