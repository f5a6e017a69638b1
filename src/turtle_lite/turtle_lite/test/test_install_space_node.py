#!/usr/bin/env python3
"""The install space holds turtlesim, turtle_lite and course_msgs (the ~save_image type), and
sourcing it alone is enough to run `rosrun turtlesim turtlesim_node` (no source tree, no devel
space on the paths).

The workspace's build directory comes from WS_BUILD_PATH (set by `./ws integration`). The
install goes under a temporary DESTDIR, so the workspace's own install/ is left alone.
"""
import os
import shutil
import subprocess
import tempfile
import unittest

import rosgraph
import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, spawn, wait_for
from turtle_lite.testing import PoseRecorder

INSTALL_DEADLINE_S = 300.0  # an incremental build plus the copy; generous on a loaded machine


def cache_value(build_dir, key):
    """A value of the build directory's CMakeCache.txt."""
    with open(os.path.join(build_dir, "CMakeCache.txt"), encoding="utf-8") as cache:
        for line in cache:
            if line.startswith(key + ":"):
                return line.split("=", 1)[1].strip()
    raise AssertionError(f"{key} not in {build_dir}/CMakeCache.txt")


class InstallSpaceTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        build_dir = os.environ.get("WS_BUILD_PATH")
        if not build_dir or not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
            raise AssertionError("WS_BUILD_PATH must name the workspace's build directory "
                                 "(run this test through ./ws integration)")
        cls.destdir = tempfile.mkdtemp(prefix="install_space_")
        prefix = cache_value(build_dir, "CMAKE_INSTALL_PREFIX")
        done = subprocess.run(["cmake", "--build", build_dir, "--target", "install"],
                              env=dict(os.environ, DESTDIR=cls.destdir), capture_output=True,
                              text=True, timeout=INSTALL_DEADLINE_S, check=False)
        if done.returncode != 0:
            raise AssertionError("install failed:\n" + done.stdout[-3000:] + done.stderr[-3000:])
        cls.install = cls.destdir + prefix

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.destdir, ignore_errors=True)

    def in_install(self, command):
        """argv running command in a fresh login-like environment that has sourced only the
        install space: the master's address, and nothing of the source or devel space."""
        env = {"PATH": "/usr/bin:/bin", "HOME": os.environ.get("HOME", "/root"),
               "ROS_MASTER_URI": rosgraph.get_master_uri(), "ROS_HOSTNAME": "localhost",
               "PYTHONUNBUFFERED": "1"}
        return ["env", "-i", *(f"{k}={v}" for k, v in env.items()),
                "bash", "-c", f'source "{self.install}/setup.bash" && {command}']

    def run_installed(self, command):
        done = subprocess.run(self.in_install(command), capture_output=True, text=True,
                              timeout=START_DEADLINE_S, check=False)
        self.assertEqual(done.returncode, 0, done.stderr)
        return done.stdout.strip()

    def test_the_packages_are_installed(self):
        for package in ("turtlesim", "turtle_lite", "course_msgs"):
            self.assertEqual(self.run_installed(f"rospack find {package}"),
                             f"{self.install}/share/{package}")
        self.assertIn("string name", self.run_installed("rossrv show turtlesim/Spawn"))
        self.assertIn("string path", self.run_installed("rossrv show course_msgs/SaveImage"))

    def test_rosrun_turtlesim_node_from_the_install_space(self):
        sim = spawn(self.in_install("exec rosrun turtlesim turtlesim_node __name:=installed_sim "
                                   "/turtle1:=/installed_turtle"))
        self.addCleanup(sim.stop)
        poses = PoseRecorder("/installed_turtle/pose", keep=1)
        self.addCleanup(poses.close)
        wait_for(lambda: poses.count() > 0 or sim.proc.poll() is not None, START_DEADLINE_S,
                 "a pose from the installed turtlesim_node")
        self.assertIsNone(sim.proc.poll(), sim.output())
        self.assertEqual(self.run_installed("rostopic type /installed_turtle/pose"),
                         "turtlesim/Pose")
        wait_for(lambda: sim.lines_with("Spawning turtle [turtle1]"), EVENT_DEADLINE_S,
                 "the installed simulator's spawn log line")


if __name__ == "__main__":
    rospy.init_node("test_install_space")
    rostest.rosrun("turtle_lite", "install_space", InstallSpaceTest)
