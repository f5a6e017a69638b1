"""stageros's services and latched extras: reset_positions, ~save_image, /map and trails."""
import rospy
from course_common.save_image import answer_save_image
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import OccupancyGrid
from std_srvs.srv import Empty, EmptyResponse
from tf2_msgs.msg import TFMessage

from stage_lite.srv import SaveImage, SaveImageResponse

from . import map_msg
from . import world_picture as picture

#: Longest side of a ~save_image picture, px (about 27 px/m on the lesson's 58.7 m floor).
IMAGE_MAX_PX = 1600


class _PackedGrid(OccupancyGrid):
    """An OccupancyGrid that serialises a body packed by map_msg (genpy packs int8[] per cell)."""

    __slots__ = ('_body',)

    def __init__(self, body):
        super().__init__()
        self._body = body

    def serialize(self, buff):
        buff.write(self._body)


class StageServices:
    """reset_positions, ~save_image, the optional /map, and the trails the pictures show."""

    def __init__(self, node):
        self.node = node
        self.trails = picture.Trails(len(node.world.robots))
        self._image_base = None
        self._angles = [[r.local_angles() for r in robot.rangers] for robot in node.world.robots]
        self._latched = []
        if node.params.publish_map:
            self._publish_map()
        self.reset_srv = rospy.Service('reset_positions', Empty, self.handle_reset)
        # an extra of stage_lite's: off until asked for, so the interface stays stageros's
        self.image_srv = (rospy.Service('~save_image', SaveImage, self.handle_save_image)
                          if node.params.save_image_service else None)

    # -------------------------------------------------------------- called under node.lock
    def after_step(self):
        for i, robot in enumerate(self.node.world.robots):
            x, y, _ = robot.pose
            self.trails.add(i, x, y)

    def robot_views(self):
        """RobotView of every robot now (call under node.lock)."""
        views = []
        for i, robot in enumerate(self.node.world.robots):
            rangers = tuple(picture.RangerView((r.pose[0], r.pose[1], r.pose[3]),
                                               self._angles[i][k], r.ranges.copy())
                            for k, r in enumerate(robot.rangers))
            views.append(picture.RobotView(
                pose=tuple(robot.pose), size=tuple(robot.size[:2]),
                origin=tuple(robot.origin[:2]), color=tuple(robot.color_rgb),
                rangers=rangers, trail=self.trails.get(i)))
        return views

    # -------------------------------------------------------------- services
    def handle_reset(self, _req):
        with self.node.lock:
            self.node.world.reset()
            self.trails.clear()
        return EmptyResponse()

    def handle_save_image(self, req):
        return SaveImageResponse(answer_save_image(
            req.path, self.node.params.image_path, self.save_image, 'world',
            'could not save the image'))

    def save_image(self, path):
        """Writes the world's picture to path (absolute); returns the path written."""
        if self._image_base is None:
            occupancy = self.node.world.occupancy()
            starts = [r.start_pose for r in self.node.world.robots]
            view = picture.fit_view(picture.world_bounds(occupancy, starts),
                                    IMAGE_MAX_PX, IMAGE_MAX_PX)
            self._image_base = (view, picture.floor_image(view, occupancy))
        view, base = self._image_base
        with self.node.lock:
            robots = self.robot_views()
        return picture.save_png(path, picture.render(view, base, robots))

    # -------------------------------------------------------------- /map
    def _publish_map(self):
        node = self.node
        frame = 'map' if node.params.tf2_frames else '/map'
        cells, res, ox, oy = map_msg.map_grid(node.world.occupancy(),
                                              node.params.map_resolution_m)
        grid_pub = rospy.Publisher('/map', OccupancyGrid, queue_size=1, latch=True)
        grid_pub.publish(_PackedGrid(map_msg.grid_body(0, 0, frame, cells, res, ox, oy)))
        # map -> odom is the identity: odometry starts at the world pose (Stage 4.3's gps).
        static = TFMessage()
        for names in node.names:
            ts = TransformStamped()
            ts.header.frame_id = frame
            ts.child_frame_id = names.odom_frame
            ts.transform.rotation.w = 1.0
            static.transforms.append(ts)
        static_pub = rospy.Publisher('/tf_static', TFMessage, queue_size=1, latch=True)
        static_pub.publish(static)
        self._latched = [grid_pub, static_pub]
        rospy.loginfo('stageros: /map %d x %d cells at %g m, frame %s',
                      cells.shape[1], cells.shape[0], res, frame)
