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

from ..model.jit import njit

_U32 = struct.Struct('<I')
HEADER_STAMP = struct.Struct('<III')  # a Header's seq, secs, nsecs
_CLOCK = struct.Struct('<III')        # length 8, secs, nsecs
_POSE = struct.Struct('<7d')
_TWIST = struct.Struct('<6d')
_SCAN_FIELDS = struct.Struct('<7f')
_TRANSFORM = struct.Struct('<7d')
#: Odometry's two covariance matrices: stageros leaves them all zero.
_ZERO_COVARIANCE = bytes(36 * 8)


def twist_command(body):
    """(linear.x, linear.y, angular.z) of a geometry_msgs/Twist's serialised body (6
    float64: linear x, y, z, angular x, y, z); ValueError if it is not 48 bytes."""
    if len(body) != _TWIST.size:
        raise ValueError('a Twist is %d bytes, not %d' % (_TWIST.size, len(body)))
    vx, vy, _, _, _, wz = _TWIST.unpack(body)
    return vx, vy, wz


def uint32_bytes(n):
    """A ROS uint32 (an array's or a string's length)."""
    return _U32.pack(n)


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


def frame_of(body_parts):
    """The TCPROS frame of a message's serialised parts: their length, then them."""
    body = b''.join(body_parts)
    return _U32.pack(len(body)) + body


def clock_frame(secs, nsecs):
    """rosgraph_msgs/Clock."""
    return _CLOCK.pack(8, secs, nsecs)


class ScanTemplate:
    """The fixed part of one ranger's LaserScan (frame and geometry), packed once."""

    def __init__(self, frame_id, angle_min, angle_increment, samples, range_min, range_max):
        self.frame_id = string_bytes(frame_id)
        # stageros: angle_max = +fov/2 = angle_min + increment * (samples - 1); no
        # time_increment or scan_time (Stage's ranger has neither).
        self.fields = _SCAN_FIELDS.pack(angle_min, -angle_min, angle_increment, 0.0, 0.0,
                                        range_min, range_max)
        self.samples = samples


def tf_frame(transforms, count=None):
    """tf2_msgs/TFMessage of already serialised geometry_msgs/TransformStamped (count: how
    many transforms they hold, if not one each)."""
    return frame_of((_U32.pack(len(transforms) if count is None else count), *transforms))


# ---- every robot's frames of a step at once ----------------------------------------------
# A swarm's stageros packs N odometries, N ground truths, N scans and 2..3 N transforms a
# step: one call per message was most of its step. A FrameBatch keeps all frames of a kind
# in one buffer, their constant bytes (frame ids, covariances, scan geometry) written once,
# and writes each changing field for every frame in one kernel call.

class FrameBatch:
    """Frames in one buffer. Each frame is a list of parts: bytes (constant) or
    (field name, byte count) (written each step with write()/fill()). ``frames[i]`` is
    frame i (its uint32 length first) as a memoryview of the buffer: send it before the
    next write."""

    def __init__(self, frames_parts):
        starts = {}
        chunks = []
        offset = 0
        spans = []
        for parts in frames_parts:
            body = sum(len(p) if isinstance(p, bytes) else p[1] for p in parts)
            chunks.append(_U32.pack(body))
            spans.append((offset, offset + 4 + body))
            offset += 4
            for part in parts:
                if isinstance(part, bytes):
                    chunks.append(part)
                    offset += len(part)
                else:
                    name, size = part
                    starts.setdefault(name, []).append((offset, size))
                    chunks.append(bytes(size))
                    offset += size
        self.buffer = np.frombuffer(bytearray(b''.join(chunks)), np.uint8)
        view = memoryview(self.buffer)
        self.frames = [view[a:b] for a, b in spans]
        self._fields = {name: (np.array([s for s, _ in places], np.int64),
                               np.array([n for _, n in places], np.int64),
                               sum(n for _, n in places))
                        for name, places in starts.items()}

    def write(self, name, values):
        """Field `name` of every frame, in order, from values' bytes (an array whose bytes
        are those of the fields in a row: e.g. (n, 7) float64 for n poses)."""
        starts, sizes, total = self._fields[name]
        data = np.ascontiguousarray(values).view(np.uint8).reshape(-1)
        if data.size != total:
            raise ValueError('field %s takes %d bytes, not %d' % (name, total, data.size))
        _scatter(self.buffer, starts, sizes, data)

    def fill(self, name, value):
        """Field `name` of every frame := the same bytes `value`."""
        starts, sizes, _ = self._fields[name]
        _fill(self.buffer, starts, sizes, np.frombuffer(value, np.uint8))


@njit(cache=True)
def _scatter(buffer, starts, sizes, data):
    k = 0
    for i in range(starts.size):
        s = starts[i]
        for j in range(sizes[i]):
            buffer[s + j] = data[k]
            k += 1


@njit(cache=True)
def _fill(buffer, starts, sizes, value):
    for i in range(starts.size):
        s = starts[i]
        for j in range(sizes[i]):
            buffer[s + j] = value[j]


@njit(cache=True)
def _yaw_quaternions(yaws, out):
    # yaw_quaternion's arithmetic, term for term (signed zeros included)
    cp = cr = 1.0
    sp = sr = 0.0
    for i in range(yaws.size):
        half = yaws[i] * 0.5
        cy, sy = math.cos(half), math.sin(half)
        out[i, 0] = sr * cp * cy - cr * sp * sy
        out[i, 1] = cr * sp * cy + sr * cp * sy
        out[i, 2] = cr * cp * sy - sr * sp * cy
        out[i, 3] = cr * cp * cy + sr * sp * sy


@njit(cache=True)
def _matrix_round_trips(q, out):
    # matrix_round_trip's arithmetic, term for term
    for n in range(q.shape[0]):
        x, y, z, w = q[n, 0], q[n, 1], q[n, 2], q[n, 3]
        s = 2.0 / (x * x + y * y + z * z + w * w)
        xs, ys, zs = x * s, y * s, z * s
        wx, wy, wz = w * xs, w * ys, w * zs
        xx, xy, xz = x * xs, x * ys, x * zs
        yy, yz, zz = y * ys, y * zs, z * zs
        m = np.empty((3, 3))
        m[0, 0], m[0, 1], m[0, 2] = 1.0 - (yy + zz), xy - wz, xz + wy
        m[1, 0], m[1, 1], m[1, 2] = xy + wz, 1.0 - (xx + zz), yz - wx
        m[2, 0], m[2, 1], m[2, 2] = xz - wy, yz + wx, 1.0 - (xx + yy)
        trace = m[0, 0] + m[1, 1] + m[2, 2]
        if trace > 0.0:
            r = math.sqrt(trace + 1.0)
            out[n, 3] = r * 0.5
            r = 0.5 / r
            out[n, 0] = (m[2, 1] - m[1, 2]) * r
            out[n, 1] = (m[0, 2] - m[2, 0]) * r
            out[n, 2] = (m[1, 0] - m[0, 1]) * r
        else:
            if m[0, 0] < m[1, 1]:
                i = 2 if m[1, 1] < m[2, 2] else 1
            else:
                i = 2 if m[0, 0] < m[2, 2] else 0
            j, k = (i + 1) % 3, (i + 2) % 3
            r = math.sqrt(m[i, i] - m[j, j] - m[k, k] + 1.0)
            out[n, i] = r * 0.5
            r = 0.5 / r
            out[n, 3] = (m[k, j] - m[j, k]) * r
            out[n, j] = (m[j, i] + m[i, j]) * r
            out[n, k] = (m[k, i] + m[i, k]) * r


def yaw_quaternions(yaws):
    """yaw_quaternion of each yaw: (n, 4) float64, bit for bit."""
    yaws = np.ascontiguousarray(yaws, np.float64)
    out = np.empty((yaws.size, 4))
    _yaw_quaternions(yaws, out)
    return out


def matrix_round_trips(quaternions):
    """matrix_round_trip of each (n, 4) quaternion, bit for bit."""
    quaternions = np.ascontiguousarray(quaternions, np.float64)
    out = np.empty((len(quaternions), 4))
    _matrix_round_trips(quaternions, out)
    return out


def transform_quaternions(yaws):
    """transform_quaternion of each yaw: (n, 4) float64, bit for bit."""
    return matrix_round_trips(yaw_quaternions(yaws))


def pose_rows(poses, quaternions):
    """(n, 7) rows x, y, z = 0 and the quaternion: an Odometry's pose, a transform's
    translation and rotation; poses (n, 2+) x, y first."""
    rows = np.zeros((len(poses), 7), '<f8')
    rows[:, 0:2] = poses[:, 0:2]
    rows[:, 3:7] = quaternions
    return rows


def odometry_parts(frame_id, child_frame_id):
    """A FrameBatch frame of nav_msgs/Odometry: fields 'stamp' (seq, secs, nsecs), 'pose'
    (7 float64), 'twist' (6 float64); both covariances zero, as stageros fills them."""
    return [('stamp', HEADER_STAMP.size), frame_id, child_frame_id, ('pose', _POSE.size),
            _ZERO_COVARIANCE, ('twist', _TWIST.size), _ZERO_COVARIANCE]


def odometry_rows(poses, twists, quaternions):
    """(pose rows, twist rows) for odometry_parts' fields: poses (n, 3) x, y, yaw; twists
    (n, 3) vx, vy, wz; quaternions (n, 4) of the yaws (yaw_ or transform_quaternions)."""
    twist_rows = np.zeros((len(poses), 6), '<f8')
    twist_rows[:, 0:2] = twists[:, 0:2]
    twist_rows[:, 5] = twists[:, 2]
    return pose_rows(poses, quaternions), twist_rows


def scan_parts(template):
    """A FrameBatch frame of sensor_msgs/LaserScan from a ScanTemplate: fields 'stamp',
    'ranges' and 'intensities' (samples float32 each)."""
    count = _U32.pack(template.samples)
    size = 4 * template.samples
    return [('stamp', HEADER_STAMP.size), template.frame_id, template.fields,
            count, ('ranges', size), count, ('intensities', size)]


def transform_parts(parent, child, xyz_yaw=None):
    """TransformStamped parts for a tf FrameBatch: field 'stamp' (seq 0, secs, nsecs),
    then the transform: fixed (xyz_yaw given: x, y, z, yaw) or field 'moving' (7 float64:
    x, y, z and transform_quaternion's rotation)."""
    if xyz_yaw is None:
        motion = ('moving', _TRANSFORM.size)
    else:
        x, y, z, yaw = xyz_yaw
        motion = _TRANSFORM.pack(x, y, z, *transform_quaternion(yaw))
    return [('stamp', HEADER_STAMP.size), parent, child, motion]
