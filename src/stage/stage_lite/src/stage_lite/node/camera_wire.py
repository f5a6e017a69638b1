"""stageros's camera messages as TCPROS frames (pure, no rospy): image, depth, camera_info and
the base_link -> camera transform, packed from the model's arrays (stage_lite.wire's way).

Layouts: sensor_msgs/Image = header, uint32 height, uint32 width, string encoding, uint8
is_bigendian, uint32 step, uint8[] data; sensor_msgs/CameraInfo = header, uint32 height,
uint32 width, string distortion_model, float64[] D, float64[9] K, float64[9] R,
float64[12] P, uint32 binning_x, uint32 binning_y, RegionOfInterest (uint32 x_offset,
y_offset, height, width, uint8 do_rectify).

What stageros 1.8.0 puts in them (src/stageros.cpp):
- image: "rgba8", step = 4 w, the rows flipped from OpenGL's (row 0 the top);
- depth, with ~is_depth_canonical true (default): "32FC1", metres, a value <= near made
  -inf and >= far +inf (REP 118; so where nothing was drawn: +inf); false: "16UC1",
  (int)(metres * 1000), 0 where that is <= (int)(near * 1000) or >= (int)(far * 1000);
- camera_info: D four zeros (distortion_model empty), K = [fx 0 cx; 0 fy cy; 0 0 1],
  R identity, P = [fx 0 cx 0; 0 fy cy 0; 0 0 1 0], binning 0, roi zero;
- is_bigendian 0 everywhere.
"""
import math
import struct

import numpy as np

from .wire import HEADER_STAMP, frame_of, matrix_round_trip, string_bytes

_U32 = struct.Struct('<I')
_SIZE = struct.Struct('<II')
_STEP = struct.Struct('<BI')
_TRANSFORM = struct.Struct('<7d')
_INFO_TAIL = struct.Struct('<II4IB')    # binning x, y; roi x, y, height, width, do_rectify
RGBA8 = 'rgba8'
DEPTH_32F = '32FC1'
DEPTH_16U = '16UC1'


def _image(seq, secs, nsecs, frame_id, height, width, encoding, step, data):
    return frame_of((HEADER_STAMP.pack(seq, secs, nsecs), frame_id, _SIZE.pack(height, width),
                   string_bytes(encoding), _STEP.pack(0, step), _U32.pack(len(data)), data))


def image_frame(seq, secs, nsecs, frame_id, rgba):
    """sensor_msgs/Image "rgba8" of an (h, w, 4) uint8 array, row 0 the top; frame_id as
    string_bytes()."""
    h, w = rgba.shape[:2]
    data = np.ascontiguousarray(rgba, np.uint8).tobytes()
    return _image(seq, secs, nsecs, frame_id, h, w, RGBA8, 4 * w, data)


def stageros_depth(depth, near, far, canonical=True):
    """The depth values stageros sends of Stage's (h, w) float32 depth (see the module
    docstring): float32 with -inf/+inf, or uint16 millimetres with 0 out of range."""
    d = np.asarray(depth, np.float32)
    if canonical:
        out = d.copy()
        out[d <= near] = -np.inf
        out[d >= far] = np.inf
        return out
    mm = np.trunc(d.astype(np.float64) * 1000.0)
    lo, hi = int(near * 1000), int(far * 1000)
    return np.where((mm <= lo) | (mm >= hi), 0, mm).astype(np.uint16)


def depth_frame(seq, secs, nsecs, frame_id, depth, near, far, canonical=True):
    """sensor_msgs/Image of Stage's depth as stageros sends it (32FC1 or 16UC1)."""
    values = stageros_depth(depth, near, far, canonical)
    h, w = values.shape
    data = np.ascontiguousarray(values, '<f4' if canonical else '<u2').tobytes()
    return _image(seq, secs, nsecs, frame_id, h, w, DEPTH_32F if canonical else DEPTH_16U,
                  (4 if canonical else 2) * w, data)


def camera_info_frame(seq, secs, nsecs, frame_id, width, height, fx, fy, cx, cy):
    """sensor_msgs/CameraInfo as stageros fills it."""
    k = (fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0)
    r = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    p = (fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0)
    return frame_of((HEADER_STAMP.pack(seq, secs, nsecs), frame_id, _SIZE.pack(height, width),
                   string_bytes(''), _U32.pack(4), struct.pack('<4d', 0.0, 0.0, 0.0, 0.0),
                   struct.pack('<9d', *k), struct.pack('<9d', *r), struct.pack('<12d', *p),
                   _INFO_TAIL.pack(0, 0, 0, 0, 0, 0, 0)))


def rpy_quaternion(roll, pitch, yaw):
    """tf's Quaternion::setRPY(roll, pitch, yaw): (x, y, z, w)."""
    hy, hp, hr = yaw * 0.5, pitch * 0.5, roll * 0.5
    cy, sy = math.cos(hy), math.sin(hy)
    cp, sp = math.cos(hp), math.sin(hp)
    cr, sr = math.cos(hr), math.sin(hr)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def camera_transform_bytes(secs, nsecs, parent, child, xyz, rpy):
    """geometry_msgs/TransformStamped base_link -> camera (seq 0), the rotation setRPY's
    after a trip through tf::Transform, as stageros sends it."""
    q = matrix_round_trip(rpy_quaternion(*rpy))
    return b''.join((HEADER_STAMP.pack(0, secs, nsecs), parent, child,
                     _TRANSFORM.pack(*xyz, *q)))
