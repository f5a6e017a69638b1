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
HEADER_STAMP = struct.Struct('<III')  # a Header's seq, secs, nsecs
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
    """(x, y, z, w) of a rotation by yaw about z as tf's Quaternion::setRPY(0, 0, yaw) makes
    it (stageros's odom: createQuaternionMsgFromYaw), signed zeros included."""
    half = yaw * 0.5
    cy, sy = math.cos(half), math.sin(half)
    cp = cr = 1.0    # cos(0 * 0.5)
    sp = sr = 0.0    # sin(0 * 0.5)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def transform_quaternion(yaw):
    """yaw_quaternion(yaw) after a trip through a tf::Transform, as stageros's ground truth
    and its transforms are sent: Matrix3x3::setRotation, then getRotation (Bullet's
    algorithm; it gives -q for yaws between -180 and -120 degrees, and may change the last
    bit)."""
    return matrix_round_trip(yaw_quaternion(yaw))


def matrix_round_trip(quaternion):
    """(x, y, z, w) after tf::Matrix3x3::setRotation and getRotation (Bullet's algorithm), as
    a tf::Transform made from it gives it back."""
    x, y, z, w = quaternion
    s = 2.0 / (x * x + y * y + z * z + w * w)
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    m = ((1.0 - (yy + zz), xy - wz, xz + wy),
         (xy + wz, 1.0 - (xx + zz), yz - wx),
         (xz - wy, yz + wx, 1.0 - (xx + yy)))
    trace = m[0][0] + m[1][1] + m[2][2]
    q = [0.0, 0.0, 0.0, 0.0]
    if trace > 0.0:
        r = math.sqrt(trace + 1.0)
        q[3] = r * 0.5
        r = 0.5 / r
        q[0] = (m[2][1] - m[1][2]) * r
        q[1] = (m[0][2] - m[2][0]) * r
        q[2] = (m[1][0] - m[0][1]) * r
    else:
        i = (2 if m[1][1] < m[2][2] else 1) if m[0][0] < m[1][1] else \
            (2 if m[0][0] < m[2][2] else 0)
        j, k = (i + 1) % 3, (i + 2) % 3
        r = math.sqrt(m[i][i] - m[j][j] - m[k][k] + 1.0)
        q[i] = r * 0.5
        r = 0.5 / r
        q[3] = (m[k][j] - m[j][k]) * r
        q[j] = (m[j][i] + m[i][j]) * r
        q[k] = (m[k][i] + m[i][k]) * r
    return tuple(q)


def _frame(body_parts):
    body = b''.join(body_parts)
    return _U32.pack(len(body)) + body


def clock_frame(secs, nsecs):
    """rosgraph_msgs/Clock."""
    return _CLOCK.pack(8, secs, nsecs)


def odometry_frame(seq, secs, nsecs, frame_id, child_frame_id, pose, twist,
                   quaternion=yaw_quaternion):
    """nav_msgs/Odometry; frame ids as string_bytes(); pose (x, y, yaw), twist (vx, vy, wz);
    quaternion: how stageros makes the orientation (odom: yaw_quaternion, ground truth:
    transform_quaternion).

    z, roll and pitch are 0 and both covariances are zero, as stageros fills them.
    """
    x, y, yaw = pose
    vx, vy, wz = twist
    return _frame((HEADER_STAMP.pack(seq, secs, nsecs), frame_id, child_frame_id,
                   _POSE.pack(x, y, 0.0, *quaternion(yaw)), _ZERO_COVARIANCE,
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
        return _frame((HEADER_STAMP.pack(seq, secs, nsecs), self.frame_id, self.fields,
                       _U32.pack(r.size), r.tobytes(), _U32.pack(i.size), i.tobytes()))


def transform_bytes(secs, nsecs, parent, child, x, y, z, yaw):
    """One geometry_msgs/TransformStamped (seq 0, as tf's broadcaster leaves it); the
    rotation as stageros's tf::Transform gives it back (transform_quaternion)."""
    return b''.join((HEADER_STAMP.pack(0, secs, nsecs), parent, child,
                     _TRANSFORM.pack(x, y, z, *transform_quaternion(yaw))))


def tf_frame(transforms):
    """tf2_msgs/TFMessage of already packed transform_bytes()."""
    return _frame((_U32.pack(len(transforms)), *transforms))
