"""stageros's camera messages and names (camera_wire, camera_names): the hand-packed frames
deserialised by genpy's own classes, REP 118 depth, the tf rotation, mapName's camera names."""
import math

import numpy as np
import pytest
from sensor_msgs.msg import CameraInfo, Image
from stage_lite.node import camera_wire, wire
from stage_lite.node.camera_names import camera_names
from tf2_msgs.msg import TFMessage

FRAME = wire.string_bytes('/robot_0/camera')


def _body(frame):
    (length,) = np.frombuffer(frame[:4], '<u4')
    assert length == len(frame) - 4
    return frame[4:]


def test_image_rgba8_row_0_on_top():
    rgba = np.arange(3 * 2 * 4, dtype=np.uint8).reshape(3, 2, 4)
    msg = Image().deserialize(_body(camera_wire.image_frame(4, 1, 2, FRAME, rgba)))
    assert (msg.header.seq, msg.header.stamp.secs, msg.header.stamp.nsecs) == (4, 1, 2)
    assert (msg.header.frame_id, msg.encoding, msg.height, msg.width, msg.step,
            msg.is_bigendian) == ('/robot_0/camera', 'rgba8', 3, 2, 8, 0)
    assert np.array_equal(np.frombuffer(msg.data, np.uint8).reshape(3, 2, 4), rgba)


def test_depth_32fc1_in_metres_with_infinities():
    depth = np.array([[0.2, 0.5, 7.99], [8.0, 3.0, 0.1]], np.float32)
    msg = Image().deserialize(_body(camera_wire.depth_frame(0, 0, 0, FRAME, depth, 0.2, 8.0)))
    assert (msg.encoding, msg.step) == ('32FC1', 12)
    got = np.frombuffer(msg.data, '<f4').reshape(2, 3)
    assert got.tolist() == [[-math.inf, 0.5, np.float32(7.99)], [math.inf, 3.0, -math.inf]]


def test_depth_16uc1_in_millimetres_zero_out_of_range():
    depth = np.array([[0.2, 0.5, 7.99], [8.0, 3.0005, 0.201]], np.float32)
    msg = Image().deserialize(_body(camera_wire.depth_frame(0, 0, 0, FRAME, depth, 0.2, 8.0,
                                                            canonical=False)))
    assert (msg.encoding, msg.step) == ('16UC1', 6)
    # (int)(d * 1000) truncates: float32 7.99 is 7.98999977
    assert np.frombuffer(msg.data, '<u2').reshape(2, 3).tolist() == [[0, 500, 7989],
                                                                      [0, 3000, 201]]


def test_camera_info():
    msg = CameraInfo().deserialize(_body(camera_wire.camera_info_frame(
        1, 2, 3, FRAME, 32, 24, 22.85, 32.97, 16.0, 12.0)))
    assert (msg.header.frame_id, msg.width, msg.height, msg.distortion_model) == \
        ('/robot_0/camera', 32, 24, '')
    assert list(msg.D) == [0.0] * 4
    assert list(msg.K) == [22.85, 0, 16.0, 0, 32.97, 12.0, 0, 0, 1]
    assert list(msg.R) == [1, 0, 0, 0, 1, 0, 0, 0, 1]
    assert list(msg.P) == [22.85, 0, 16.0, 0, 0, 32.97, 12.0, 0, 0, 0, 1, 0]
    assert (msg.binning_x, msg.binning_y, msg.roi.width, msg.roi.do_rectify) == (0, 0, 0, False)


def test_camera_transform():
    roll, yaw = math.radians(90) - math.pi, -math.pi / 2
    packed = camera_wire.camera_transform_bytes(5, 6, wire.string_bytes('base_link'),
                                                wire.string_bytes('camera'), (0.1, 0, 0.25),
                                                (roll, 0.0, yaw))
    msg = TFMessage().deserialize(_body(wire.tf_frame([packed])))
    t = msg.transforms[0]
    assert (t.header.frame_id, t.child_frame_id) == ('base_link', 'camera')
    assert (t.transform.translation.x, t.transform.translation.z) == (0.1, 0.25)
    q = t.transform.rotation
    want = camera_wire.rpy_quaternion(roll, 0.0, yaw)
    # the same rotation (q or -q)
    dot = abs(q.x * want[0] + q.y * want[1] + q.z * want[2] + q.w * want[3])
    assert dot == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize('index, robots, cameras, use_names, want_image, want_frame', [
    (0, 1, 1, False, ['image'], ['camera']),
    (0, 1, 2, False, ['/image_0', '/image_1'], ['/camera_0', '/camera_1']),
    (1, 4, 1, False, ['/robot_1/image'], ['/robot_1/camera']),
    (1, 4, 2, False, ['/robot_1/image_0', '/robot_1/image_1'],
     ['/robot_1/camera_0', '/robot_1/camera_1']),
    (0, 1, 1, True, ['/r0/image'], ['/r0/camera']),
])
def test_names(index, robots, cameras, use_names, want_image, want_frame):
    names = camera_names(index, 'r0', robots, cameras, use_names)
    assert [n.image for n in names] == want_image
    assert [n.frame for n in names] == want_frame
    assert [n.depth for n in names] == [i.replace('image', 'depth') for i in want_image]
    assert [n.camera_info for n in names] == [i.replace('image', 'camera_info')
                                              for i in want_image]


def test_tf2_frames_drop_the_slash():
    assert camera_names(1, '', 4, 1, tf2_frames=True)[0].frame == 'robot_1/camera'
    with pytest.raises(ValueError):
        camera_names(4, '', 4, 1)
