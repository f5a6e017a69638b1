"""course_common's etc/ros: the roscore.xml every master of a sourced shell loads.

The env hook points ROS_ETC_DIR (rospkg's /etc/ros) at course_common/etc/ros; roslaunch (for
roscore, and for roslaunch and rostest when they start a master) then reads its roscore.xml:
Debian's, and /rosout_disable_topics_generation set to its default. These fail if a sourced
shell's roslaunch reads another file, if Debian's roscore.xml gains or loses anything ours
lacks, or if a link of etc/ros leaves /etc/ros. A real master holding the parameter is
test/roscore_params.test's.
"""
import os
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2]
ETC = PACKAGE / 'etc' / 'ros'
WORKSPACE = PACKAGE.parents[1]
DEBIAN_ROSCORE = Path('/etc/ros/roscore.xml')
PARAM = ('param', (('name', 'rosout_disable_topics_generation'), ('value', 'false')))


def elements(path):
    """(tag, sorted attributes) of each element under the launch, in document order."""
    return [(e.tag, tuple(sorted(e.attrib.items()))) for e in ET.parse(path).getroot().iter()
            if e.tag != 'launch']


def sourced(command):
    """command's output in bash after sourcing the workspace's devel space."""
    setup = WORKSPACE / 'devel' / 'setup.bash'
    if not setup.is_file():
        pytest.skip('no devel space at %s (./ws build)' % setup)
    env = {k: v for k, v in os.environ.items() if k != 'ROS_ETC_DIR'}
    done = subprocess.run(['bash', '-c', 'source "%s" && %s' % (setup, command)], env=env,
                          capture_output=True, text=True, timeout=60, check=True)
    return done.stdout.strip()


def test_a_sourced_shell_starts_masters_with_the_workspace_roscore_xml():
    assert sourced('echo "$ROS_ETC_DIR"') == str(ETC)
    got = sourced('/usr/bin/python3 -c "import roslaunch.config as c;'
                  ' print(c.get_roscore_filename())"')
    assert Path(got) == ETC / 'roscore.xml'


@pytest.mark.skipif(not DEBIAN_ROSCORE.is_file(), reason='no /etc/ros/roscore.xml here')
def test_the_roscore_xml_is_debians_and_one_parameter():
    ours, debian = elements(ETC / 'roscore.xml'), elements(DEBIAN_ROSCORE)
    assert [e for e in ours if e != PARAM] == debian
    assert ours.count(PARAM) == 1


def test_the_rest_of_etc_ros_is_debians():
    links = {p.name: os.readlink(p) for p in ETC.iterdir() if p.is_symlink()}
    assert links, 'etc/ros links nothing of /etc/ros'
    for name, target in links.items():
        assert target == '/etc/ros/' + name, name
    assert {p.name for p in ETC.iterdir()} == set(links) | {'roscore.xml'}
