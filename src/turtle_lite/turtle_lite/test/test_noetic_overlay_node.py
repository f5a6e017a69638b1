#!/usr/bin/env python3
"""Noetic code as written: `#!/usr/bin/env python` rospy nodes of an overlay workspace.

A throwaway overlay (made in a temporary directory) holds one package with two such nodes, as
students write them: `talker`, installed with catkin_install_python, and `plain_talker`, an
executable file in scripts/ that is not installed. It is built on top of this workspace's devel
space, and its nodes run under rosrun and roslaunch with PATH starting with a directory whose
`python` (and, in one case, `python3` too) is a venv's, which cannot import rospy, the way a
pyenv or conda `python` comes first. Each node reports the interpreter it ran under in a
parameter; it must be Debian's.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest
from course_common.testing import wait_for

BUILD_DEADLINE_S = 300.0  # cmake + catkin_make of a one-package overlay on a loaded machine
RUN_DEADLINE_S = 60.0  # rosrun / roslaunch of one short-lived node
PARAM_NS = '/noetic_overlay'

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>noetic_lab</name>
  <version>0.0.1</version>
  <description>A student's package, written for Noetic.</description>
  <maintainer email="student@example.org">Student</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>rospy</exec_depend>
</package>
"""

CMAKELISTS = """cmake_minimum_required(VERSION 3.0.2)
project(noetic_lab)
find_package(catkin REQUIRED)
catkin_package()
catkin_install_python(PROGRAMS nodes/talker DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
"""

# The lab's shape: `#!/usr/bin/env python`, import rospy, report, exit.
NODE = """#!/usr/bin/env python
import os
import sys

import rospy

rospy.init_node('{name}')
rospy.set_param('{ns}/{name}/' + os.environ['NOETIC_CASE'], sys.executable)
"""

LAUNCH = """<launch>
  <node pkg="noetic_lab" type="talker" name="talker"/>
  <node pkg="noetic_lab" type="plain_talker" name="plain_talker"/>
</launch>
"""


def _write(path, text, executable=False):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(text)
    if executable:
        os.chmod(path, 0o755)


def _underlay_devel():
    """This workspace's devel space: the first CMAKE_PREFIX_PATH entry with a setup.bash."""
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(':'):
        if prefix and os.path.isfile(os.path.join(prefix, 'setup.bash')) \
                and os.path.isfile(os.path.join(prefix, '.catkin')):
            return prefix
    raise AssertionError('no catkin devel space on CMAKE_PREFIX_PATH: %r'
                         % os.environ.get('CMAKE_PREFIX_PATH'))


class NoeticOverlayTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_noetic_overlay')
        # The nodes report through these parameters: none may be left from an earlier run on
        # the same master (rostest starts a fresh one, a developer's roscore does not).
        if rospy.has_param(PARAM_NS):
            rospy.delete_param(PARAM_NS)
        cls.tmp = tempfile.mkdtemp(prefix='noetic_overlay_')
        cls.underlay = _underlay_devel()
        # A python that cannot import rospy: a venv of Debian's python3 without its dist-packages.
        venv = os.path.join(cls.tmp, 'venv')
        subprocess.run(['/usr/bin/python3', '-m', 'venv', '--without-pip', venv], check=True)
        # Shim dirs: only `python` foreign (pyenv-like, python3 still Debian's), or both.
        cls.shims = {}
        for case, names in (('python', ('python',)), ('python_and_python3', ('python', 'python3'))):
            shim = os.path.join(cls.tmp, 'shim_' + case)
            os.makedirs(shim)
            for name in names:
                # A script, not a symlink: a symlinked venv python outside the venv finds no
                # pyvenv.cfg and imports rospy after all.
                _write(os.path.join(shim, name),
                       '#!/bin/sh\nexec %s "$@"\n' % os.path.join(venv, 'bin', 'python'),
                       executable=True)
            cls.shims[case] = shim
            probe = subprocess.run([os.path.join(shim, 'python'), '-c', 'import rospy'],
                                   capture_output=True)
            assert probe.returncode != 0, 'the shim imports rospy: the test would prove nothing'
        pkg = os.path.join(cls.tmp, 'overlay', 'src', 'noetic_lab')
        _write(os.path.join(pkg, 'package.xml'), PACKAGE_XML)
        _write(os.path.join(pkg, 'CMakeLists.txt'), CMAKELISTS)
        _write(os.path.join(pkg, 'nodes', 'talker'),
               NODE.format(name='talker', ns=PARAM_NS), executable=True)
        _write(os.path.join(pkg, 'scripts', 'plain_talker'),
               NODE.format(name='plain_talker', ns=PARAM_NS), executable=True)
        _write(os.path.join(pkg, 'launch', 'talk.launch'), LAUNCH)
        # Built the way a student does it in a shell whose `python` is the foreign one.
        build = cls.shell('python', 'source %s/setup.bash && cd %s && catkin_make'
                          % (cls.underlay, os.path.join(cls.tmp, 'overlay')), BUILD_DEADLINE_S)
        assert build.returncode == 0, 'the overlay does not build:\n' + build.stdout[-3000:]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def shell(cls, case, script, timeout_s, tool='catkin_make'):
        """Runs script in bash with the case's shim dir first on PATH; returns the result."""
        env = dict(os.environ, PATH=cls.shims[case] + ':' + os.environ['PATH'],
                   NOETIC_CASE='%s_%s' % (tool, case))
        for var in ('PYTHONPATH', 'ROS_PACKAGE_PATH', 'CMAKE_PREFIX_PATH', 'PYTHONHOME'):
            env.pop(var, None)
        return subprocess.run(['bash', '-c', script], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True,
                              timeout=timeout_s)

    def run_sourced(self, case, tool, args):
        overlay = os.path.join(self.tmp, 'overlay', 'devel', 'setup.bash')
        command = '%s %s' % (tool, args)
        result = self.shell(case, 'source %s && %s' % (overlay, command), RUN_DEADLINE_S, tool)
        self.assertEqual(result.returncode, 0, '%s (%s first):\n%s'
                         % (command, case, result.stdout[-3000:]))
        return result

    def assert_debian_python(self, node, tool, case, output):
        key = '%s/%s/%s_%s' % (PARAM_NS, node, tool, case)
        executable = wait_for(lambda: rospy.get_param(key, None), RUN_DEADLINE_S,
                              'parameter %s' % key)
        self.assertEqual(os.path.dirname(executable), '/usr/bin', output)

    def test_rosrun_with_foreign_python_first(self):
        for case in self.shims:
            for node in ('talker', 'plain_talker'):
                with self.subTest(case=case, node=node):
                    result = self.run_sourced(case, 'rosrun', 'noetic_lab ' + node)
                    self.assert_debian_python(node, 'rosrun', case, result.stdout)

    def test_roslaunch_with_foreign_python_first(self):
        for case in self.shims:
            with self.subTest(case=case):
                # The master is the test's: roslaunch exits once both nodes have exited.
                result = self.run_sourced(case, 'roslaunch', 'noetic_lab talk.launch')
                for node in ('talker', 'plain_talker'):
                    self.assert_debian_python(node, 'roslaunch', case, result.stdout)


if __name__ == '__main__':
    rostest.rosrun('turtle_lite', 'noetic_overlay', NoeticOverlayTest, sys.argv)
