"""The hand-packed frames deserialise, with genpy's own classes, to what stageros sends."""
import io
import math

import numpy as np
import pytest
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import OccupancyGrid, Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from stage_lite.node import map_msg, wire
from tf2_msgs.msg import TFMessage

TOL = 1e-12  # float64 fields round-trip exactly; float32 ones are compared with approx below


def _body(frame):
    (length,) = np.frombuffer(frame[:4], '<u4')
    assert length == len(frame) - 4
    return frame[4:]


def one_frame(parts, stamp, **fields):
    """The frame of one FrameBatch of parts, its header (seq, secs, nsecs) and fields set."""
    batch = wire.FrameBatch([parts])
    batch.fill('stamp', wire.HEADER_STAMP.pack(*stamp))
    for name, values in fields.items():
        batch.write(name, values)
    return bytes(batch.frames[0])


def odometry_frame(stamp, frame_id, child, pose, twist, quaternions=wire.yaw_quaternions):
    poses, twists = wire.odometry_rows(np.array([pose]), np.array([twist]),
                                       quaternions([pose[2]]))
    return one_frame(wire.odometry_parts(wire.string_bytes(frame_id), wire.string_bytes(child)),
                     stamp, pose=poses, twist=twists)


def test_clock():
    msg = Clock().deserialize(_body(wire.clock_frame(12, 300_000_000)))
    assert (msg.clock.secs, msg.clock.nsecs) == (12, 300_000_000)


@pytest.mark.parametrize('child', ['', 'base_footprint'])
def test_odometry(child):
    frame = odometry_frame((7, 3, 500), '/robot_0/odom', child, (-11.5, 23.5, math.pi / 2),
                           (0.2, 0.0, -0.3))
    msg = Odometry().deserialize(_body(frame))
    assert (msg.header.seq, msg.header.stamp.secs, msg.header.stamp.nsecs) == (7, 3, 500)
    assert (msg.header.frame_id, msg.child_frame_id) == ('/robot_0/odom', child)
    p, q = msg.pose.pose.position, msg.pose.pose.orientation
    assert (p.x, p.y, p.z) == (-11.5, 23.5, 0.0)
    assert (q.x, q.y, q.z, q.w) == pytest.approx((0, 0, math.sqrt(0.5), math.sqrt(0.5)), abs=TOL)
    t = msg.twist.twist
    assert (t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z) == \
        (0.2, 0.0, 0.0, 0.0, 0.0, -0.3)
    assert not any(msg.pose.covariance) and not any(msg.twist.covariance)


def test_laser_scan_fields_as_stage_fills_them():
    fov, samples = math.radians(270.25), 1081
    template = wire.ScanTemplate('/robot_1/base_laser_link', -fov / 2, fov / (samples - 1),
                                 samples, 0.0, 30.0)
    ranges = np.linspace(0.5, 30.0, samples, dtype=np.float32)
    intensities = np.ones(samples, np.float32)
    frame = one_frame(wire.scan_parts(template), (4, 1, 100_000_000), ranges=ranges,
                      intensities=intensities)
    msg = LaserScan().deserialize(_body(frame))
    assert msg.header.frame_id == '/robot_1/base_laser_link'
    assert msg.angle_min == pytest.approx(-2.35838, abs=1e-5)
    assert msg.angle_max == pytest.approx(2.35838, abs=1e-5)
    assert msg.angle_increment == pytest.approx(0.00436736, abs=1e-8)
    assert (msg.time_increment, msg.scan_time, msg.range_min, msg.range_max) == (0, 0, 0, 30)
    assert np.array_equal(np.asarray(msg.ranges, np.float32), ranges)
    assert np.array_equal(np.asarray(msg.intensities, np.float32), intensities)


def test_tf_message_holds_every_transform():
    s = wire.string_bytes
    moving = np.array([[1.0, 2.0, 0.0, *wire.transform_quaternion(0.5)]])
    parts = [wire.uint32_bytes(2),
             *wire.transform_parts(s('/robot_0/odom'), s('/robot_0/base_footprint')),
             *wire.transform_parts(s('/robot_0/base_link'), s('/robot_0/base_laser_link'),
                                   (0.05, 0.0, 0.25, 0.0))]
    msg = TFMessage().deserialize(_body(one_frame(parts, (0, 2, 0), moving=moving)))
    assert [(t.header.frame_id, t.child_frame_id) for t in msg.transforms] == \
        [('/robot_0/odom', '/robot_0/base_footprint'),
         ('/robot_0/base_link', '/robot_0/base_laser_link')]
    laser = msg.transforms[1].transform
    assert (laser.translation.x, laser.translation.y, laser.translation.z) == (0.05, 0.0, 0.25)
    assert msg.transforms[0].transform.rotation.z == pytest.approx(math.sin(0.25), abs=TOL)
    assert msg.transforms[0].header.stamp.secs == 2


@pytest.mark.parametrize('degrees, flipped', [(0, False), (30, False), (-100, False),
                                              (-119, False), (-121, True), (-170, True),
                                              (170, False)])
def test_transform_quaternion_is_tfs_round_trip(degrees, flipped):
    # stageros sends ground truth and tf rotations through a tf::Transform: the same
    # rotation, as -q for yaws between -180 and -120 degrees (Bullet's getRotation)
    yaw = math.radians(degrees)
    q = wire.yaw_quaternion(yaw)
    t = wire.transform_quaternion(yaw)
    assert (q[0], q[1]) == (0.0, 0.0) and (t[0], t[1]) == (0.0, 0.0)
    sign = -1.0 if flipped else 1.0
    assert (t[2], t[3]) == pytest.approx((sign * q[2], sign * q[3]), abs=1e-15)
    assert 2 * math.atan2(t[2], t[3]) == pytest.approx(yaw + (2 * math.pi if flipped else 0.0),
                                                       abs=1e-12)


def test_ground_truth_orientation_through_the_transform():
    frame = odometry_frame((1, 0, 0), '/robot_0/odom', '', (0.0, 0.0, math.radians(-150)),
                           (0.0, 0.0, 0.0), wire.transform_quaternions)
    q = Odometry().deserialize(_body(frame)).pose.pose.orientation
    assert q.w < 0 and (q.z, q.w) == wire.transform_quaternion(math.radians(-150))[2:]


def test_occupancy_grid_rows_start_at_the_lowest_y():
    grid = np.zeros((4, 6), bool)
    grid[0, 5] = True          # lowest row, last column
    grid[3, 0] = True
    cells, res, ox, oy = map_msg.map_grid((grid, -1.0, 2.0, 0.5), 0.5)
    body = map_msg.grid_body(5, 0, 'map', cells, res, ox, oy)
    msg = OccupancyGrid().deserialize(body)
    assert (msg.info.width, msg.info.height, msg.info.resolution) == (6, 4, 0.5)
    assert (msg.info.origin.position.x, msg.info.origin.position.y) == (-1.0, 2.0)
    assert msg.info.origin.orientation.w == 1.0
    data = np.asarray(msg.data).reshape(4, 6)
    assert data[0, 5] == 100 and data[3, 0] == 100 and data.sum() == 200


def test_map_grid_refuses_a_bad_resolution():
    with pytest.raises(ValueError):
        map_msg.map_grid((np.zeros((2, 2), bool), 0, 0, 0.02), 0.0)


def test_twist_command_reads_a_serialised_twist_and_refuses_other_sizes():
    buff = io.BytesIO()
    Twist(linear=Vector3(0.5, -0.25, 9.0), angular=Vector3(7.0, 8.0, -1.5)).serialize(buff)
    body = buff.getvalue()      # what a cmd_vel frame carries after its length
    assert wire.twist_command(body) == (0.5, -0.25, -1.5)
    with pytest.raises(ValueError, match='a Twist is 48 bytes, not 47'):
        wire.twist_command(body[:47])
