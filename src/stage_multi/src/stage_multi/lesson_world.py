"""The synchronisation lesson's world, in one place: its file, where its robots start, and the
stageros command line that runs it (no rospy).

The world is this package's world/willow-multi-erratic.world, as the lesson's slides say
("copy the world subdirectory from the stage_multi package"); multi_sync.launch and
stage_multi.launch name it with $(find stage_multi).
"""
import os

import rospkg

WORLD_FILE = 'willow-multi-erratic.world'
#: Each robot's start (x, y in m, heading 0), robot_0 .. robot_3: the lesson's 2 x 2 group.
STARTS = ((-11.5, 23.5), (-13.5, 23.5), (-11.5, 21.5), (-13.5, 21.5))
#: stageros as a user starts it (stage_ros's interface).
STAGEROS = ('rosrun', 'stage_ros', 'stageros')


def world_path():
    """The lesson's world file (in the devel or install space's stage_multi)."""
    return os.path.join(rospkg.RosPack().get_path('stage_multi'), 'world', WORLD_FILE)


def stageros_command(*options, world=None):
    """`rosrun stage_ros stageros OPTIONS WORLD` (the lesson's world unless another is given)."""
    return [*STAGEROS, *options, world or world_path()]
