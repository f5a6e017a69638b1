"""What stageros's pictures show of the world, kept in one place (pure: no rospy).

WorldView holds what a picture needs beyond the world itself: each robot's trail and its
rangers' beam angles. The window (gui) and ~save_image (stage_services) both draw from one:
record() after every step and robots() under the node's lock, pictures outside it.
"""
from . import world_picture as picture


class WorldView:
    """The robots' trails and views of a world, and its floor fitted to a picture size."""

    def __init__(self, world):
        self.world = world
        self.trails = picture.Trails(len(world.robots))
        self._angles = [[r.local_angles() for r in robot.rangers] for robot in world.robots]
        self._floors = {}

    def record(self):
        """After a step: each robot's position joins its trail."""
        for i, robot in enumerate(self.world.robots):
            x, y, _ = robot.pose
            self.trails.add(i, x, y)

    def clear(self):
        """After reset_positions: the trails start again."""
        self.trails.clear()

    def robots(self):
        """RobotView of every robot now (copies: draw them outside the lock)."""
        views = []
        for i, robot in enumerate(self.world.robots):
            rangers = tuple(picture.RangerView((r.pose[0], r.pose[1], r.pose[3]),
                                               self._angles[i][k], r.ranges.copy())
                            for k, r in enumerate(robot.rangers))
            views.append(picture.RobotView(
                pose=tuple(robot.pose), size=tuple(robot.size[:2]),
                origin=tuple(robot.origin[:2]), color=tuple(robot.color_rgb),
                rangers=rangers, trail=self.trails.get(i)))
        return views

    def floor(self, width_px, height_px):
        """(view, floor image) of the world fitted to width x height px, made once per size.
        The world's static parts only: no lock needed."""
        key = (width_px, height_px)
        if key not in self._floors:
            occupancy = self.world.occupancy()
            starts = [r.start_pose for r in self.world.robots]
            view = picture.fit_view(picture.world_bounds(occupancy, starts), width_px,
                                    height_px)
            self._floors[key] = (view, picture.floor_image(view, occupancy))
        return self._floors[key]
