"""turtlesim_node's fast path: each tick's poses and colours as pre-packed TCPROS frames.

A turtle's pose and colour go only to topics with subscribers, packed straight from the
world's arrays and written by rospy_internals.write_frame from the tick thread (no message
objects, no rospy send queue: see that module for the measured reason).
"""
import struct

from course_common.rospy_internals import has_subscribers, write_frame

#: TCPROS frames of turtlesim/Pose (5 float32) and turtlesim/Color (3 uint8): a
#: little-endian uint32 length, then the fields in order (the md5sums fix this layout).
POSE_FRAME = struct.Struct('<I5f')
POSE_BYTES = 20
COLOR_FRAME = struct.Struct('<I3B')
COLOR_BYTES = 3


def publish_tick(handles, result):
    """Send result's pose and colour i to handles[i]'s subscribers (None handles skipped).

    result is a World.step() result: ``poses`` (N x 5: x, y, theta, linear, angular) and
    ``colors`` (N x 3: r, g, b) arrays in the order of ``handles``; each array is converted
    to Python numbers only if some turtle's topic has a subscriber.
    """
    poses = None
    colors = None
    for i, handle in enumerate(handles):
        if handle is None:
            continue
        if has_subscribers(handle.pose_pub):
            if poses is None:
                poses = result.poses.tolist()
            write_frame(handle.pose_pub, POSE_FRAME.pack(POSE_BYTES, *poses[i]))
        if has_subscribers(handle.color_pub):
            if colors is None:
                colors = result.colors.tolist()
            write_frame(handle.color_pub, COLOR_FRAME.pack(COLOR_BYTES, *colors[i]))
