"""stageros's services and latched extras: reset_positions, ~save_image and /map."""
import rospy
from course_common.save_image import answer_save_image, write_png
from course_msgs.srv import SaveImage, SaveImageResponse
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import OccupancyGrid
from std_srvs.srv import Empty, EmptyResponse
from tf2_msgs.msg import TFMessage

from . import map_msg


class _PackedGrid(OccupancyGrid):
    """An OccupancyGrid that serialises a body packed by map_msg (genpy packs int8[] per cell)."""

    __slots__ = ('_body',)

    def __init__(self, body):
        super().__init__()
        self._body = body

    def serialize(self, buff):
        buff.write(self._body)


class StageServices:
    """reset_positions, ~save_image and the optional /map of a world.

    world: the world (its floor plan, for /map); params: the node's StagerosParams; names:
    each robot's RobotNames (for /map's transforms); reset(): every robot back to its start
    (the node's, under its lock); picture(): the world's picture as ~save_image draws it.
    """

    def __init__(self, world, params, names, reset, picture):
        self.params = params
        self._reset = reset
        self._picture = picture
        self._latched = self._publish_map(world, names) if params.publish_map else []
        self.reset_srv = rospy.Service('reset_positions', Empty, self.handle_reset)
        # an extra of stage_lite's: off until asked for, so the interface stays stageros's
        self.image_srv = (rospy.Service('~save_image', SaveImage, self.handle_save_image)
                          if params.save_image_service else None)

    def handle_reset(self, _req):
        self._reset()
        return EmptyResponse()

    def handle_save_image(self, req):
        return SaveImageResponse(answer_save_image(
            req.path, self.params.image_path, self.save_image, 'world',
            'could not save the image'))

    def save_image(self, path):
        """Writes the world's picture to path (absolute); returns the path written."""
        return write_png(path, self._picture())

    def _publish_map(self, world, names):
        """Latches /map and map -> odom transforms; returns the publishers (kept alive)."""
        frame = 'map' if self.params.tf2_frames else '/map'
        cells, res, ox, oy = map_msg.map_grid(world.occupancy(),
                                              self.params.map_resolution_m)
        grid_pub = rospy.Publisher('/map', OccupancyGrid, queue_size=1, latch=True)
        grid_pub.publish(_PackedGrid(map_msg.grid_body(0, 0, frame, cells, res, ox, oy)))
        # map -> odom is the identity: odometry starts at the world pose (Stage 4.3's gps).
        static = TFMessage()
        for robot_names in names:
            ts = TransformStamped()
            ts.header.frame_id = frame
            ts.child_frame_id = robot_names.odom_frame
            ts.transform.rotation.w = 1.0
            static.transforms.append(ts)
        static_pub = rospy.Publisher('/tf_static', TFMessage, queue_size=1, latch=True)
        static_pub.publish(static)
        rospy.loginfo('stageros: /map %d x %d cells at %g m, frame %s',
                      cells.shape[1], cells.shape[0], res, frame)
        return [grid_pub, static_pub]
