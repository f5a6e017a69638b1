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
import subprocess
import sys
import time

import rosgraph
import rospy
from course_common.testing import cpu_ticks, rss_mb, spawn, wait_for
from course_common.testing.master import Roscore
from tf2_msgs.msg import TFMessage
from turtlesim.srv import Spawn

TURTLES = 50
WINDOW_S = 10.0  # CPU time comes in 10 ms ticks: 10 s resolves 0.1 % of a core
START_DEADLINE_S = 180.0  # 50 Python processes starting on a shared 2-core machine
CLK_TCK = os.sysconf('SC_CLK_TCK')


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
    procs = [spawn(c, stop_timeout_s=20.0) for c in commands]
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
            p.interrupt()  # all at once: each takes a moment to shut down
        for p in procs:
            p.stop()
        wait_for(lambda: not subscribed_pose_topics(master), START_DEADLINE_S,
                   'the broadcasters of %s gone' % label)


def main():
    core = Roscore().start()
    sim = None
    try:
        master = rosgraph.Master('/tf_bench')
        sim = spawn(['rosrun', 'turtlesim', 'turtlesim_node'])
        rospy.init_node('tf_bench', disable_signals=True)
        rospy.wait_for_service('/spawn', 60.0)
        spawn_turtle = rospy.ServiceProxy('/spawn', Spawn)
        for i in range(2, TURTLES + 1):
            spawn_turtle(1.0 + (i % 8) * 1.2, 1.0 + (i // 8) * 1.2, 0.0, 'turtle%d' % i)
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
                proc.stop()


if __name__ == '__main__':
    sys.exit(main())
