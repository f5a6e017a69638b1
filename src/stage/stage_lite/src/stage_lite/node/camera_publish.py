"""stageros's camera output: per camera on a robot, image, depth and camera_info, and the
base_link -> camera transform, as stage_ros 1.8.0 publishes them (names: camera_names,
packing: camera_wire).

stageros sends them at every world step (every interval_sim), each camera's latest frame
(Stage makes a new one every update_interval, 100 ms by default), stamped with the step's
sim time, from the first update on; image and depth only to subscribers; camera_info and the
transform only when the image or the depth has a subscriber.
"""
from course_common.publishers import unqueued_publisher
from course_common.rospy_internals import has_subscribers
from sensor_msgs.msg import CameraInfo, Image

from . import camera_wire
from .camera_names import camera_names
from .wire import string_bytes


class CameraOutput:
    """One camera's publishers and packed frame ids."""

    def __init__(self, names, view, base_frame, canonical):
        self.names = names
        self.view = view
        self.canonical = canonical
        self.image_pub = unqueued_publisher(names.image, Image)
        self.depth_pub = unqueued_publisher(names.depth, Image)
        self.info_pub = unqueued_publisher(names.camera_info, CameraInfo)
        self.frame = string_bytes(names.frame)
        self.base_frame = string_bytes(base_frame)
        self.seq = {self.image_pub: 0, self.depth_pub: 0, self.info_pub: 0}

    @property
    def publishers(self):
        return (self.image_pub, self.depth_pub, self.info_pub)

    def _next_seq(self, pub):
        # roscpp numbers the messages a publisher sends; stageros sends only to subscribers
        seq = self.seq[pub]
        self.seq[pub] = seq + 1
        return seq

    def collect(self, robot_yaw, secs, nsecs, frames, transforms):
        """Append this step's (publisher, frame)s to frames and the camera's transform to
        transforms; robot_yaw: the robot's own pose yaw (rad)."""
        v = self.view
        if not v.has_data:
            return
        image = has_subscribers(self.image_pub)
        depth = has_subscribers(self.depth_pub)
        if image:
            frames.append((self.image_pub, camera_wire.image_frame(
                self._next_seq(self.image_pub), secs, nsecs, self.frame, v.rgba)))
        if depth:
            frames.append((self.depth_pub, camera_wire.depth_frame(
                self._next_seq(self.depth_pub), secs, nsecs, self.frame, v.depth, v.near,
                v.far, self.canonical)))
        if image or depth:
            transforms.append(camera_wire.camera_transform_bytes(
                secs, nsecs, self.base_frame, self.frame, v.tf_xyz, v.tf_rpy(robot_yaw)))
            if has_subscribers(self.info_pub):
                fx, fy, cx, cy = v.intrinsics()
                frames.append((self.info_pub, camera_wire.camera_info_frame(
                    self._next_seq(self.info_pub), secs, nsecs, self.frame, v.width, v.height,
                    fx, fy, cx, cy)))


class CameraOutputs:
    """Every robot's cameras (world.cameras.by_robot), in stageros's order."""

    def __init__(self, world, robot_names, use_model_names, tf2_frames, canonical):
        self.by_robot = []
        count = len(world.robots)
        for i, (robot, rn) in enumerate(zip(world.robots, robot_names, strict=True)):
            views = world.cameras.by_robot[i]
            names = camera_names(i, robot.model_name, count, len(views), use_model_names,
                                 tf2_frames) if views else []
            self.by_robot.append([CameraOutput(n, v, rn.base_frame, canonical)
                                  for n, v in zip(names, views, strict=True)])
        self.outputs = [c for cs in self.by_robot for c in cs]
        self.publishers = [p for c in self.outputs for p in c.publishers]

    def collect(self, world, secs, nsecs, frames):
        """This step's camera frames appended to frames; returns the camera transforms."""
        transforms = []
        for robot, outputs in zip(world.robots, self.by_robot, strict=True):
            for c in outputs:
                c.collect(robot.model.pose[3], secs, nsecs, frames, transforms)
        return transforms
