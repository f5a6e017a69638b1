"""What stageros's pictures show of the world, kept in one place (pure: no rospy).

WorldView holds what a picture needs beyond the world itself: each robot's trail, its body
and its rangers' beam angles, the world's window block read as a camera and draw options,
and the floor drawn for a camera. The window (gui) and ~save_image (stage_services) both
draw from one: record() after every step and robots() under the node's lock, pictures
outside it.
"""
from . import world_picture as picture
from .camera import robots_box, window_camera, window_size

#: Floors kept drawn: the world's own view and the window's latest ones.
FLOOR_CACHE = 4


def _body_polygons(model):
    """The model's blocks as polygons in the robot frame (its geom pose applied)."""
    gx, gy, _, ga = model.geom_pose
    return tuple(picture.transformed((gx, gy, ga), b.pts) for b in model.blocks
                 if len(b.pts) >= 3)


class WorldView:
    """The robots' trails and views of a world, its window's camera and its floor pictures."""

    def __init__(self, world):
        self.world = world
        self.trails = picture.trails(len(world.robots))
        self.options = picture.draw_options(world.window)
        self._angles = [[r.local_angles() for r in robot.rangers] for robot in world.robots]
        self._bodies = [_body_polygons(robot.model) for robot in world.robots]
        self._plan = None
        self._floors = {}

    def record(self):
        """After a step: each robot's position joins its trail."""
        self.trails.add_all(self.world.robot_poses()[:, :2])

    def clear(self):
        """After reset_positions: the trails start again."""
        self.trails.clear()

    def robots(self):
        """RobotView of every robot now (copies: draw them outside the lock)."""
        views = []
        for i, robot in enumerate(self.world.robots):
            scans = tuple(picture.ScanView((r.pose[0], r.pose[1], r.pose[3]),
                                           self._angles[i][k], r.ranges.copy())
                          for k, r in enumerate(robot.rangers))
            views.append(picture.RobotView(
                pose=tuple(robot.pose), size=tuple(robot.size[:2]),
                origin=tuple(robot.origin[:2]), color=tuple(robot.color_rgb),
                scans=scans, trail=self.trails.get(i), body=self._bodies[i],
                nose=robot.model.gui_nose))
        return views

    def plan(self):
        """The world's FloorPlan (its static parts only: no lock needed), made once."""
        if self._plan is None:
            occupancy = self.world.occupancy()
            self._plan = picture.FloorPlan(occupancy, picture.world_bounds(occupancy))
        return self._plan

    def camera(self, screen_px=None):
        """The camera of the world's window block, with the robots in view where it leaves
        the centre or scale out (camera.window_camera)."""
        window = self.world.window
        box = robots_box([r.start_pose[:2] for r in self.world.robots], self.plan().extent)
        return window_camera(window, window_size(window, screen_px), box)

    def floor(self, camera, grid_on=True):
        """The floor picture of camera's view (FloorPlan.image), drawn once per view."""
        key = (camera, grid_on)
        if key not in self._floors:
            if len(self._floors) >= FLOOR_CACHE:
                self._floors.pop(next(iter(self._floors)))
            self._floors[key] = self.plan().image(camera, grid_on)
        return self._floors[key]
