"""RobotFrames: every robot's frames of a step packed at once, byte for byte the frames rospy
sends for the same messages (genpy's own classes, filled field by field as stageros fills them)."""
import io
import math
import os

import numpy as np
import pytest
from geometry_msgs.msg import Quaternion, TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from stage_lite.model.world import load_world
from stage_lite.node import wire
from stage_lite.node.names import all_robot_names
from stage_lite.node.robot_frames import RobotFrames
from tf2_msgs.msg import TFMessage

WORLDS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'worlds')


def genpy_frame(msg):
    """msg as rospy frames it: its serialised length, then its bytes."""
    buff = io.BytesIO()
    msg.serialize(buff)
    return wire.uint32_bytes(len(buff.getvalue())) + buff.getvalue()


def stamped(msg, seq, secs, nsecs, frame_id):
    msg.header.seq, msg.header.frame_id = seq, frame_id
    msg.header.stamp.secs, msg.header.stamp.nsecs = secs, nsecs
    return msg


def odometry(seq, secs, nsecs, frame_id, child, pose, twist, quaternion):
    msg = stamped(Odometry(), seq, secs, nsecs, frame_id)
    msg.child_frame_id = child
    msg.pose.pose.position.x, msg.pose.pose.position.y = pose[0], pose[1]
    msg.pose.pose.orientation = Quaternion(*quaternion(pose[2]))
    msg.twist.twist.linear.x, msg.twist.twist.linear.y = twist[0], twist[1]
    msg.twist.twist.angular.z = twist[2]
    return msg


def scan(seq, secs, nsecs, frame_id, ranger):
    msg = stamped(LaserScan(), seq, secs, nsecs, frame_id)
    msg.angle_min, msg.angle_max = ranger.angle_min, -ranger.angle_min
    msg.angle_increment = ranger.angle_increment
    msg.range_min, msg.range_max = ranger.range_min, ranger.range_max
    msg.ranges, msg.intensities = list(ranger.ranges), list(ranger.intensities)
    return msg


def transform(secs, nsecs, parent, child, x, y, z, yaw):
    msg = stamped(TransformStamped(), 0, secs, nsecs, parent)
    msg.child_frame_id = child
    msg.transform.translation.x, msg.transform.translation.y = x, y
    msg.transform.translation.z = z
    msg.transform.rotation = Quaternion(*wire.transform_quaternion(yaw))
    return msg


def one_by_one(world, names, seq, secs, nsecs, odom_child_frame):
    """The frames of genpy's messages, robot by robot, as stageros fills them."""
    odom, truth, scans, transforms = [], [], [], []
    for robot, n in zip(world.robots, names, strict=True):
        child = n.footprint_frame if odom_child_frame else ''
        odom.append(genpy_frame(odometry(seq, secs, nsecs, n.odom_frame, child,
                                         robot.odom_pose, robot.command, wire.yaw_quaternion)))
        truth.append(genpy_frame(odometry(seq, secs, nsecs, n.odom_frame, '', robot.pose,
                                          robot.truth_twist, wire.transform_quaternion)))
        scans.append([genpy_frame(scan(seq, secs, nsecs, frame, r))
                      for frame, r in zip(n.laser_frames, robot.rangers, strict=True)])
        x, y, yaw = robot.odom_pose
        transforms.append(transform(secs, nsecs, n.odom_frame, n.footprint_frame,
                                    x, y, 0.0, yaw))
        transforms.append(transform(secs, nsecs, n.footprint_frame, n.base_frame,
                                    0.0, 0.0, 0.0, 0.0))
        for frame, r in zip(n.laser_frames, robot.rangers, strict=True):
            transforms.append(transform(secs, nsecs, n.base_frame, frame, *r.pose))
    return odom, truth, scans, genpy_frame(TFMessage(transforms=transforms))


def driven_world(name, steps):
    world = load_world(os.path.join(WORLDS, name))
    for k in range(steps):
        for i in range(len(world.robots)):
            world.set_command(i, 0.4 - 0.1 * i, 0.05 * (i % 2), 0.9 - 0.6 * i + 0.1 * k)
        world.step()
    return world


@pytest.mark.parametrize('name, odom_child_frame', [
    ('node_four_robots.world', False), ('node_two_rangers.world', True),
    ('node_one_robot.world', False)])
def test_every_frame_equals_the_one_by_one_frame(name, odom_child_frame):
    world = driven_world(name, 30)
    names = all_robot_names([r.model_name for r in world.robots],
                            [len(r.rangers) for r in world.robots])
    frames = RobotFrames(world, names, odom_child_frame)
    for seq in (29, 30):        # twice: the second fill overwrites every changing byte
        world.step()
        frames.fill(seq, 3 + seq, 100_000_000)
        odom, truth, scans, tf = one_by_one(world, names, seq, 3 + seq, 100_000_000,
                                            odom_child_frame)
        assert [bytes(f) for f in frames.odom] == odom
        assert [bytes(f) for f in frames.truth] == truth
        assert [[bytes(f) for f in robot] for robot in frames.scans] == scans
        assert bytes(frames.tf) == tf
    assert frames.tf_count == sum(2 + len(r.rangers) for r in world.robots)


def test_only_the_kinds_asked_for_are_written():
    world = driven_world('node_four_robots.world', 5)
    names = all_robot_names([r.model_name for r in world.robots],
                            [len(r.rangers) for r in world.robots])
    frames = RobotFrames(world, names, False)
    frames.fill(1, 2, 3)
    before = [bytes(f) for f in frames.truth], bytes(frames.tf)
    world.step()
    frames.fill(2, 3, 4, odom=True, truth=False, scans=False, tf=False)
    assert ([bytes(f) for f in frames.truth], bytes(frames.tf)) == before
    assert [bytes(f) for f in frames.odom] == one_by_one(world, names, 2, 3, 4, False)[0]


YAWS = [0.0, -0.0, math.pi, -math.pi, math.pi / 2, -math.pi / 2, math.radians(-150),
        math.radians(-120), math.radians(-180) + 1e-15, 1e-300, -1e-300, 2.5, -2.5, 3.1, -3.1]


def test_the_quaternion_kernels_equal_the_python_bit_for_bit():
    yaws = np.concatenate([YAWS, np.random.default_rng(7).uniform(-math.pi, math.pi, 20000)])
    batch_yaw = wire.yaw_quaternions(yaws)
    batch_tf = wire.transform_quaternions(yaws)
    for k, yaw in enumerate(yaws.tolist()):
        # tobytes: equal bits, signed zeros included
        assert np.array(wire.yaw_quaternion(yaw)).tobytes() == batch_yaw[k].tobytes(), yaw
        assert np.array(wire.transform_quaternion(yaw)).tobytes() == batch_tf[k].tobytes(), yaw


def test_a_frame_batch_refuses_values_of_the_wrong_size():
    batch = wire.FrameBatch([[b'ab', ('x', 8)], [('x', 8), b'c']])
    batch.write('x', np.array([1.5, -2.0]))
    assert bytes(batch.frames[0]) == wire.uint32_bytes(10) + b'ab' + np.float64(1.5).tobytes()
    assert bytes(batch.frames[1]) == wire.uint32_bytes(9) + np.float64(-2.0).tobytes() + b'c'
    with pytest.raises(ValueError, match='field x takes 16 bytes, not 8'):
        batch.write('x', np.array([1.5]))
    batch.fill('x', bytes(range(8)))
    assert bytes(batch.frames[1])[4:12] == bytes(range(8))


def test_a_world_without_robots_has_an_empty_tf_message(tmp_path):
    path = tmp_path / 'no_robot.world'
    path.write_text('size [10 10 1]\nmodel ( name "box" pose [1 1 0 0] size [0.5 0.5 0.5] )\n')
    world = load_world(str(path))
    frames = RobotFrames(world, [], False)
    world.step()
    frames.fill(1, 2, 3)
    assert (frames.odom, frames.truth, frames.scans) == ([], [], [])
    assert bytes(frames.tf) == genpy_frame(TFMessage())
