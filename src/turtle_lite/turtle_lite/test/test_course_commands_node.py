#!/usr/bin/env python3
"""The course's turtlesim commands, typed as the slides print them, against this workspace.

The slides of the four decks say `rosrun turtlesim ...`, `rostopic type /turtle1/pose |
rosmsg show`, `rostopic pub /turtle1/cmd_vel ...`, include "turtlesim/Pose.h" in C++ and
import turtlesim.msg in Python. Each test runs one of them as a user would, in a shell, and
checks what the user would see. The simulator itself is started with the slide's
`rosrun turtlesim turtlesim_node`.
"""
import os
import subprocess
import unittest

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, spawn, wait_for
from turtle_lite.testing import (
    CENTER,
    POSE_TOL,
    ColorRecorder,
    PoseRecorder,
    run_teleop,
)
from turtlesim.srv import TeleportAbsolute

CLIENTS_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "clients")
BANNER_LAST = "Use arrow keys to move the turtle. 'q' to quit."
UP_ARROW = b"\x1b[A"
MOVED_M = 0.05  # a turtle that has moved this far from where it stood has clearly been driven

# turtlesim 0.10's definitions as `rosmsg show` / `rossrv show` print them.
POSE_FIELDS = ["float32 x", "float32 y", "float32 theta", "float32 linear_velocity",
               "float32 angular_velocity"]
SPAWN_FIELDS = ["float32 x", "float32 y", "float32 theta", "string name", "---", "string name"]
# md5sums of the real turtlesim's Pose and Spawn: a node built against turtlesim elsewhere
# only connects to ours if these match.
POSE_MD5 = "863b248d5016ca62ea2e895ae5265cf9"
SPAWN_MD5 = "0b2d2e872a8e2887d5ed626f2bf2c561"


def shell(command):
    """Run a command line as a user types it; return its stdout lines (fails on non-zero)."""
    done = subprocess.run(["bash", "-c", command], capture_output=True, text=True,
                          timeout=START_DEADLINE_S, check=False)
    if done.returncode != 0:
        raise AssertionError(f"{command!r} exited {done.returncode}: {done.stderr.strip()}")
    return [line.rstrip() for line in done.stdout.splitlines() if line.strip()]


class CourseCommandsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = spawn(["rosrun", "turtlesim", "turtlesim_node"])
        cls.turtle1 = PoseRecorder("/turtle1/pose", keep=1)
        wait_for(lambda: cls.turtle1.count() > 0, START_DEADLINE_S,
                 "turtle1's first pose from `rosrun turtlesim turtlesim_node`")
        cls.teleport1 = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)

    @classmethod
    def tearDownClass(cls):
        cls.sim.stop()

    def setUp(self):
        # Every test starts with turtle1 at rest at home (commands time out after 1 s).
        self.turtle1.wait_latest(lambda p: p.linear_velocity == 0, "turtle1 at rest",
                                 START_DEADLINE_S)
        self.teleport1(CENTER, CENTER, 0.0)
        self.turtle1.wait_latest(
            lambda p: abs(p.x - CENTER) < POSE_TOL and abs(p.y - CENTER) < POSE_TOL,
            "turtle1 back home")

    def wait_moved(self, recorder, start_x, what):
        recorder.wait_latest(lambda p: p.x > start_x + MOVED_M, what)

    def start_teleop(self, *remaps):
        teleop = run_teleop(("rosrun", "turtlesim", "turtle_teleop_key", *remaps))
        self.addCleanup(teleop.close)
        wait_for(lambda: BANNER_LAST in teleop.output(), START_DEADLINE_S, "the teleop banner")
        return teleop

    def press_up_until(self, teleop, recorder, start_x, what):
        """Press the up arrow until the turtle moves (the first key may beat the connection)."""
        def moved():
            teleop.send(UP_ARROW)
            return recorder.latest().x > start_x + MOVED_M
        wait_for(moved, EVENT_DEADLINE_S, what, poll_s=0.2)

    def test_rostopic_type_piped_to_rosmsg_show(self):
        self.assertEqual(shell("rostopic type /turtle1/pose"), ["turtlesim/Pose"])
        self.assertEqual(shell("rostopic type /turtle1/pose | rosmsg show"), POSE_FIELDS)
        self.assertEqual(shell("rosmsg show turtlesim/Pose"), POSE_FIELDS)
        self.assertEqual(shell("rossrv show turtlesim/Spawn"), SPAWN_FIELDS)
        self.assertEqual(shell("rosmsg md5 turtlesim/Pose"), [POSE_MD5])
        self.assertEqual(shell("rossrv md5 turtlesim/Spawn"), [SPAWN_MD5])
        self.assertIn("/turtle1/pose [turtlesim/Pose]", "\n".join(shell("rosnode info /turtlesim")))

    def test_rostopic_pub_moves_the_turtle(self):
        # As printed: without -1 or -r, rostopic publishes once, latches and keeps running.
        pub = spawn(["bash", "-c", "rostopic pub /turtle1/cmd_vel geometry_msgs/Twist "
                                  "'{linear: {x: 0.2}}'"])
        self.addCleanup(pub.stop)
        self.wait_moved(self.turtle1, CENTER, "turtle1 to move forward at 0.2 m/s")
        self.assertAlmostEqual(self.turtle1.latest().linear_velocity, 0.2, places=5)

    def test_teleop_arrow_keys_move_turtle1(self):
        teleop = self.start_teleop()
        self.press_up_until(teleop, self.turtle1, CENTER, "turtle1 to move on the up arrow")
        teleop.send(b"q")
        self.assertEqual(teleop.proc.wait(timeout=EVENT_DEADLINE_S), 0)

    def test_convoy_practice_teleop_remap_drives_robot1(self):
        # convoy practice: the leader is robot1, driven by the remapped teleop.
        shell("rosservice call /spawn 3.0 3.0 0.0 robot1")
        robot1 = PoseRecorder("/robot1/pose", keep=1)
        self.addCleanup(robot1.close)
        self.addCleanup(shell, "rosservice call /kill robot1")
        robot1.wait_latest(lambda p: True, "robot1's first pose")
        teleop = self.start_teleop("/turtle1/cmd_vel:=/robot1/cmd_vel")
        self.press_up_until(teleop, robot1, 3.0, "robot1 to move on the up arrow")
        self.assertEqual(self.turtle1.latest().linear_velocity, 0.0,
                         "turtle1 must not receive the remapped commands")

    def test_cpp_client_includes_turtlesim_headers(self):
        # test/pose_spawn_client.cpp of the turtlesim package: #include "turtlesim/Pose.h",
        # turtlesim::Spawn, built by catkin against the generated headers.
        client = spawn(["rosrun", "turtlesim", "pose_spawn_client", "cpp_turtle"])
        self.addCleanup(client.stop)
        self.assertEqual(client.wait_exit(START_DEADLINE_S), 0, client.output())
        self.assertTrue(client.lines_with("spawned cpp_turtle"), client.output())
        self.assertTrue(client.lines_with("pose x: "), client.output())
        self.assertEqual(shell("rostopic type /cpp_turtle/pose"), ["turtlesim/Pose"])
        shell("rosservice call /kill cpp_turtle")

    def test_python_client_for_turtlesim_runs_unmodified(self):
        client = spawn([os.path.join(CLIENTS_DIR, "turtlesim_client.py")])
        self.addCleanup(client.stop)
        self.assertEqual(client.wait_exit(START_DEADLINE_S), 0, client.output())
        self.assertEqual(client.lines_with("pose x:"), ["pose x: 2.00 y: 8.00 theta: 1.57"])
        # The red pen drew the teleport's line: a probe turtle placed on it sees red.
        shell("rosservice call /spawn 2.0 5.0 0.0 probe")
        probe = ColorRecorder("/probe/color_sensor")
        self.addCleanup(probe.close)
        probe.wait_rgb((255, 0, 0), "the probe on the painter's red line")
        for name in ("probe", "painter"):
            shell(f"rosservice call /kill {name}")


if __name__ == "__main__":
    rospy.init_node("test_course_commands")
    rostest.rosrun("turtle_lite", "course_commands", CourseCommandsTest)
