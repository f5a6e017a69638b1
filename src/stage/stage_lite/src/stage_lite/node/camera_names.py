"""stageros's camera topic and frame names (pure, no rospy), its mapName() rules (names.py).

With one camera on a robot: ``image``, ``depth``, ``camera_info`` and the frame ``camera``,
under the robot's prefix (relative with one robot and no ``-u``). With several: ``image_<k>``,
``depth_<k>``, ``camera_info_<k>``, frames ``camera_<k>``, which are always absolute, as
mapName's device form makes them (``/image_0`` with one robot). The camera frames hang on
the robot's ``base_link``.
"""
from dataclasses import dataclass

from .names import frame_id, prefix


@dataclass(frozen=True)
class CameraNames:
    """One camera's topics and frame id."""

    image: str
    depth: str
    camera_info: str
    frame: str


def camera_names(index, model_name, robot_count, camera_count, use_model_names=False,
                 tf2_frames=False):
    """CameraNames of each of robot ``index``'s ``camera_count`` cameras."""
    if index < 0 or robot_count < 1 or index >= robot_count or camera_count < 0:
        raise ValueError('robot %d of %d with %d cameras is not a robot'
                         % (index, robot_count, camera_count))
    p = prefix(index, model_name, robot_count, use_model_names)
    if camera_count == 1:
        return [CameraNames(p + 'image', p + 'depth', p + 'camera_info',
                            frame_id(p + 'camera', tf2_frames))]
    d = p or '/'   # per-device names are absolute even for one robot
    return [CameraNames('%simage_%d' % (d, k), '%sdepth_%d' % (d, k),
                        '%scamera_info_%d' % (d, k), frame_id('%scamera_%d' % (d, k), tf2_frames))
            for k in range(camera_count)]
