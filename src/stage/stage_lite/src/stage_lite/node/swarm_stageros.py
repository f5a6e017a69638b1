"""swarm_stageros: stageros on a generated swarm world (no rospy: it execs stageros).

    rosrun stage_ros swarm_stageros [-g] [-u] [--stageros EXE] N [ROS args]

Writes stage_lite.swarm_world's ROS swarm of N robots (world_text(N, ros=True)) to
$ROS_HOME/swarm_ros_<N>.world (~/.ros by default) and replaces itself with
`rosrun stage_ros stageros [-g] [-u] WORLD [ROS args]`, or EXE (real stageros, say) instead.
"""
import os
import sys

from stage_lite import swarm_world

USAGE = 'usage: swarm_stageros [-g] [-u] [--stageros EXE] N [ROS args]'


def parse(argv):
    """(flags, count, stageros argv prefix, ROS args) from argv[1:]; ValueError with USAGE."""
    flags, rest, count, exe = [], [], None, None
    args = list(argv)
    while args:
        a = args.pop(0)
        if a in ('-g', '-u'):
            flags.append(a)
        elif a == '--stageros' and args:
            exe = args.pop(0)
        elif count is None and not a.startswith('_') and ':=' not in a:
            try:
                count = int(a)
            except ValueError:
                raise ValueError('%r is not a robot count (%s)' % (a, USAGE)) from None
            if count < 1:
                raise ValueError('a swarm needs at least one robot, not %d' % count)
        else:
            rest.append(a)
    if count is None:
        raise ValueError('how many robots? (%s)' % USAGE)
    command = [exe] if exe else ['rosrun', 'stage_ros', 'stageros']
    return flags, count, command, rest


def world_dir():
    return os.environ.get('ROS_HOME') or os.path.join(os.path.expanduser('~'), '.ros')


def main(argv=None):
    argv = sys.argv if argv is None else argv
    try:
        flags, count, command, rest = parse(argv[1:])
    except ValueError as err:
        sys.stderr.write('[FATAL] swarm_stageros: %s\n' % err)
        sys.exit(1)
    path = swarm_world.write_worlds(world_dir(), (count,), ros=True)[count]
    argv = [*command, *flags, path, *rest]
    os.execvp(argv[0], argv)
