"""stageros's messages as ready-made TCPROS frames, packed straight from numbers and arrays.

Pure (no rospy, no message objects). A frame is a little-endian uint32 length and the ROS
serialisation of the message, what course_common.rospy_internals.write_frame sends. Laser
ranges go in as one ``ndarray.tobytes()`` (no per-beam Python work); a rospy LaserScan of
1081 beams costs a struct.pack of 1081 Python floats, twice, per robot and step.
Layouts (field order fixed by the md5sums): std_msgs/Header = uint32 seq, time stamp,
string frame_id; nav_msgs/Odometry = header, child_frame_id, pose (7 float64) + covariance
(36 float64), twist (6 float64) + covariance (36 float64); sensor_msgs/LaserScan = header,
7 float32, float32[] ranges, float32[] intensities; tf2_msgs/TFMessage = TransformStamped[]
(header, child_frame_id, translation 3 float64, rotation 4 float64); rosgraph_msgs/Clock.
"""
import math
import struct

import numpy as np

_U32 = struct.Struct('<I')
_STAMP = struct.Struct('<III')        # seq, secs, nsecs
_CLOCK = struct.Struct('<III')        # length 8, secs, nsecs
_POSE = struct.Struct('<7d')
_TWIST = struct.Struct('<6d')
_SCAN_FIELDS = struct.Struct('<7f')
_TRANSFORM = struct.Struct('<7d')
#: Odometry's two covariance matrices: stageros leaves them all zero.
_ZERO_COVARIANCE = bytes(36 * 8)


def string_bytes(text):
    """A ROS string field: uint32 length and the UTF-8 bytes."""
    data = text.encode('utf-8')
    return _U32.pack(len(data)) + data


def yaw_quaternion(yaw):
    """(x, y, z, w) of a rotation by yaw about z."""
    half = 0.5 * yaw
    return 0.0, 0.0, math.sin(half), math.cos(half)


def _frame(body_parts):
    body = b''.join(body_parts)
    return _U32.pack(len(body)) + body


def clock_frame(secs, nsecs):
    """rosgraph_msgs/Clock."""
    return _CLOCK.pack(8, secs, nsecs)


def odometry_frame(seq, secs, nsecs, frame_id, child_frame_id, pose, twist):
    """nav_msgs/Odometry; frame ids as string_bytes(); pose (x, y, yaw), twist (vx, vy, wz).

    z, roll and pitch are 0 and both covariances are zero, as stageros fills them.
    """
    x, y, yaw = pose
    vx, vy, wz = twist
    return _frame((_STAMP.pack(seq, secs, nsecs), frame_id, child_frame_id,
                   _POSE.pack(x, y, 0.0, *yaw_quaternion(yaw)), _ZERO_COVARIANCE,
                   _TWIST.pack(vx, vy, 0.0, 0.0, 0.0, wz), _ZERO_COVARIANCE))


class ScanTemplate:
    """The fixed part of one ranger's LaserScan (frame and geometry), packed once."""

    def __init__(self, frame_id, angle_min, angle_increment, samples, range_min, range_max):
        self.frame_id = string_bytes(frame_id)
        # stageros: angle_max = +fov/2 = angle_min + increment * (samples - 1); no
        # time_increment or scan_time (Stage's ranger has neither).
        self.fields = _SCAN_FIELDS.pack(angle_min, -angle_min, angle_increment, 0.0, 0.0,
                                        range_min, range_max)
        self.samples = samples

    def frame(self, seq, secs, nsecs, ranges, intensities):
        """sensor_msgs/LaserScan with ranges and intensities (float32 arrays of samples)."""
        r = np.ascontiguousarray(ranges, dtype='<f4')
        i = np.ascontiguousarray(intensities, dtype='<f4')
        return _frame((_STAMP.pack(seq, secs, nsecs), self.frame_id, self.fields,
                       _U32.pack(r.size), r.tobytes(), _U32.pack(i.size), i.tobytes()))


def transform_bytes(secs, nsecs, parent, child, x, y, z, yaw):
    """One geometry_msgs/TransformStamped (seq 0, as tf's broadcaster leaves it)."""
    return b''.join((_STAMP.pack(0, secs, nsecs), parent, child,
                     _TRANSFORM.pack(x, y, z, *yaw_quaternion(yaw))))


def tf_frame(transforms):
    """tf2_msgs/TFMessage of already packed transform_bytes()."""
    return _frame((_U32.pack(len(transforms)), *transforms))
