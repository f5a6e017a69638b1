"""Stage's `dynamic` (examples/ctrl/dynamic.cc): at start-up, prints "Creating 100 models"
(no newline: Stage's World::Load ends the line after every controller's Init) and makes 100
plain models under its own, each at Pose.random(-1, 1, -1, 1) in its frame (three drand48()
draws), resized to a 0.1 m cube and coloured blue, in that order (runtime_models.py: they
stand still, so its model must not be carried by a robot)."""
import sys

from stage_lite.model.stage_api import Pose

COUNT = 100
SIZE = (0.1, 0.1, 0.1)        # m
COLOR = (0.0, 0.0, 1.0, 1.0)  # blue


def init(model, args):
    if len(args.words()) > 1:
        raise ValueError('dynamic takes no arguments (Stage\'s ignores them), got "%s"'
                         % args.worldfile)
    sys.stdout.write('Creating %d models' % COUNT)
    sys.stdout.flush()
    world = model.world
    for _ in range(COUNT):
        child = world.create_model(model, 'model')
        child.set_pose(Pose.random(world, -1.0, 1.0, -1.0, 1.0))
        child.set_geom(Pose(), SIZE)
        child.set_color(COLOR)
