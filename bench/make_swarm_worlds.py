"""Writes Stage worlds of N swarmbots (stage_lite.swarm_world: Stage's benchmark swarmbot and
its expand_swarm controller, the hospital's floor as a tile per 1,000 robots, open).

Run: `/usr/bin/python3 bench/make_swarm_worlds.py [--ros] [OUT_DIR] [N ...]` with the devel
space sourced; defaults: build/swarm_worlds, N = 1 10 100 1000 10000 100000. Prints the paths.
--ros: the worlds for a ROS controller (swarm_ros_<N>.world: no ctrl, the 12 infrared readings
as one 12-sample sensor, which stage_ros publishes whole).
"""
import os
import sys

from stage_lite import swarm_world


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    ros = '--ros' in argv
    argv = [a for a in argv if a != '--ros']
    here = os.path.dirname(os.path.abspath(__file__))
    out_dir = argv[0] if argv else os.path.join(here, '..', 'build', 'swarm_worlds')
    counts = tuple(int(a) for a in argv[1:]) or swarm_world.COUNTS
    for n, path in swarm_world.write_worlds(out_dir, counts, ros).items():
        print('%6d swarmbots: %s' % (n, os.path.normpath(path)))


if __name__ == '__main__':
    main()
