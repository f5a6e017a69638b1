#!/usr/bin/env python3
"""rostest node: the autopilot drives at the speed set under the new or the old parameter name,
and an old name gives a deprecation warning naming the new one."""
import os
import signal
import subprocess
import threading
import unittest

import rospy
import rostest
from convoy.path import Lemniscate
from course_common.testing import wait_for
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

PKG = 'convoy'
START_DEADLINE_S = 45.0  # rosrun, rospy and the autopilot's start-up on a loaded 2-core machine
STOP_TIMEOUT_S = 20.0
EXIT_TIMEOUT_S = 60.0
# On the default eight's crossing, facing along it: the autopilot commands its full speed.
START_PATH = Lemniscate()
START_POSE = Pose(x=START_PATH.point(0.0)[0], y=START_PATH.point(0.0)[1],
                  theta=START_PATH.heading(0.0))


class Autopilot:
    """One autopilot started by the test on its own topics, its output kept for the checks."""

    def __init__(self, name, params):
        self.name = name
        self._lock = threading.Lock()
        self._commands = []
        self._sub = rospy.Subscriber('/%s/cmd_vel' % name, Twist, self._on_command)
        self._pose_pub = rospy.Publisher('/%s/pose' % name, Pose, queue_size=1)
        self.proc = subprocess.Popen(
            ['rosrun', PKG, 'autopilot', '__name:=' + name, 'pose:=/%s/pose' % name,
             'cmd_vel:=/%s/cmd_vel' % name] + ['_%s:=%s' % item for item in params.items()],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=dict(os.environ))
        self._output = None

    def _on_command(self, msg):
        with self._lock:
            self._commands.append(msg)

    def first_command(self):
        """The first command, or None after sending one more pose (called on every poll)."""
        with self._lock:
            if self._commands:
                return self._commands[0]
        self._pose_pub.publish(START_POSE)
        return None

    def running(self):
        return self.proc.poll() is None

    def output(self, timeout_s=STOP_TIMEOUT_S):
        """Everything it printed, once it has exited (killed after timeout_s); idempotent."""
        if self._output is None:
            try:
                self._output = self.proc.communicate(timeout=timeout_s)[0]
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self._output = self.proc.communicate()[0]
            self._sub.unregister()
            self._pose_pub.unregister()
        return self._output

    def stop(self):
        """Ctrl-C, then its output."""
        if self.running():
            self.proc.send_signal(signal.SIGINT)
        return self.output()


class TestAutopilotParams(unittest.TestCase):

    def _drive(self, name, params):
        """(speed of the first command, the autopilot's output) for these private params."""
        pilot = Autopilot(name, params)
        self.addCleanup(pilot.stop)
        command = wait_for(pilot.first_command, START_DEADLINE_S, 'a command from %s' % name,
                           alive=pilot.running)
        return command.linear.x, pilot.stop()

    def test_new_names_without_warning(self):
        speed, output = self._drive('autopilot_new', {'speed_mps': 0.6, 'lookahead_m': 0.9})
        self.assertAlmostEqual(speed, 0.6, places=6, msg=output)
        self.assertNotIn('deprecated', output)
        self.assertIn('at 0.60 m/s', output)

    def test_old_name_still_works_and_warns(self):
        speed, output = self._drive('autopilot_old', {'speed': 0.7, 'max_turn': 1.5})
        self.assertAlmostEqual(speed, 0.7, places=6, msg=output)
        self.assertIn('at 0.70 m/s', output)
        for old, new in (('speed', 'speed_mps'), ('max_turn', 'max_turn_radps')):
            warned = [line for line in output.splitlines()
                      if '[WARN]' in line and '~%s is deprecated' % old in line]
            self.assertTrue(warned and '~%s' % new in warned[0], output)

    def test_new_name_wins_over_old(self):
        speed, output = self._drive('autopilot_both', {'speed': 0.9, 'speed_mps': 0.4})
        self.assertAlmostEqual(speed, 0.4, places=6, msg=output)
        self.assertIn('~speed is deprecated and ignored: ~speed_mps is set too', output)

    def test_bad_value_under_old_name_is_fatal_naming_it(self):
        pilot = Autopilot('autopilot_bad_old', {'speed': -1.0})
        self.addCleanup(pilot.stop)
        output = pilot.output(EXIT_TIMEOUT_S)
        self.assertEqual(pilot.proc.returncode, 1, output)
        self.assertIn('~speed is deprecated: rename it ~speed_mps', output)
        fatal = [line for line in output.splitlines() if '[FATAL]' in line]
        self.assertTrue(fatal and '~speed' in fatal[0] and '-1.0' in fatal[0], output)
        self.assertNotIn('Traceback', output)


if __name__ == '__main__':
    rospy.init_node('test_autopilot_params')
    rostest.rosrun(PKG, 'autopilot_params', TestAutopilotParams)
