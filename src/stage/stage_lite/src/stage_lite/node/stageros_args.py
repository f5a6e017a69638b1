"""stageros's command line: ``stageros [-g] [-u] WORLD`` (pure, no rospy).

As stage_ros 1.8.0 reads it: the world file is the last argument; ``-g`` (no window) and
``-u`` (model names as namespaces) may stand anywhere before it; other arguments before it are
ignored (stageros ignores them silently; this module names them so the node can warn).
ROS's own arguments (``__name:=``, remaps) must already be removed (rospy.myargv does).
"""
from dataclasses import dataclass

USAGE = 'Usage: stageros [-g] [-u] WORLD'


class ArgsError(ValueError):
    """The command line cannot be used; the message is one line ending with the usage."""


@dataclass(frozen=True)
class StageArgs:
    """What the command line asks for."""

    world_path: str
    gui: bool = True             # no -g
    use_model_names: bool = False  # -u
    ignored: tuple = ()          # arguments before the world file that mean nothing


def parse_args(argv):
    """StageArgs from argv without the program name (ROS arguments already removed)."""
    args = list(argv)
    if not args:
        raise ArgsError('no world file given. %s' % USAGE)
    world = args[-1]
    if world in ('-g', '-u'):
        raise ArgsError('the world file must be the last argument, not %r. %s' % (world, USAGE))
    if not world.strip():
        raise ArgsError('the world file name is empty. %s' % USAGE)
    flags = args[:-1]
    return StageArgs(world_path=world, gui='-g' not in flags, use_model_names='-u' in flags,
                     ignored=tuple(a for a in flags if a not in ('-g', '-u')))
