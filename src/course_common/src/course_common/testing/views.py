"""Test support for the tf and rviz views (rostest nodes of every package).

TfPoseCheck compares tf's newest world -> <frame> transform with the newest pose on the
robot's pose topic (any message with x, y and theta: turtlesim/Pose, geometry_msgs/Pose2D).
"""

import math
import threading

import rospy
import tf2_ros

from course_common.angles import yaw_from_quaternion
from course_common.testing import wait_for

POSITION_TOL_M = 1e-4  # float32 poses through float64 transforms: far below a pose's change
YAW_TOL_RAD = 1e-4


def yaw_of(q):
    """The rotation about z of a geometry_msgs/Quaternion, as tf's euler_from_quaternion."""
    return yaw_from_quaternion(q.x, q.y, q.z, q.w)


class TfPoseCheck:
    """Listens to tf and to the pose topics of `frames` ({frame: pose topic}), whose
    messages are pose_class (x, y, theta)."""

    def __init__(self, frames, pose_class, parent='world'):
        self.parent = parent
        self.frames = dict(frames)
        self.buffer = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.buffer)
        self._lock = threading.Lock()
        self._poses = {}
        self._subs = [rospy.Subscriber(topic, pose_class, self._on_pose, callback_args=frame,
                                       queue_size=1) for frame, topic in self.frames.items()]

    def _on_pose(self, msg, frame):
        with self._lock:
            self._poses[frame] = msg

    def close(self):
        for sub in self._subs:
            sub.unregister()
        self.listener.unregister()

    def mismatch(self, frame):
        """None when tf's newest transform of frame equals its newest pose, else why not."""
        with self._lock:
            pose = self._poses.get(frame)
        if pose is None:
            return 'no pose of %s yet' % frame
        try:
            t = self.buffer.lookup_transform(self.parent, frame, rospy.Time(0)).transform
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException) as err:
            return 'no transform %s -> %s: %s' % (self.parent, frame, err)
        d_yaw = math.atan2(math.sin(yaw_of(t.rotation) - pose.theta),
                           math.cos(yaw_of(t.rotation) - pose.theta))
        if abs(t.translation.x - pose.x) > POSITION_TOL_M \
                or abs(t.translation.y - pose.y) > POSITION_TOL_M \
                or t.translation.z != 0.0 or abs(d_yaw) > YAW_TOL_RAD:
            return '%s: tf (%.4f, %.4f, %.4f, yaw %.4f) but pose (%.4f, %.4f, theta %.4f)' % (
                frame, t.translation.x, t.translation.y, t.translation.z, yaw_of(t.rotation),
                pose.x, pose.y, pose.theta)
        return None

    def wait_agree(self, timeout_s, frames=None):
        """Waits until tf agrees with every pose (of frames, default all); AssertionError names
        the last disagreement. Moving turtles agree once they stop, or between two poses."""
        frames = list(self.frames) if frames is None else list(frames)
        last = {}

        def agree():
            last['why'] = [m for m in (self.mismatch(f) for f in frames) if m]
            return not last['why']
        try:
            wait_for(agree, timeout_s, 'tf to match the poses of %s' % ', '.join(frames))
        except AssertionError as err:
            raise AssertionError('%s: %s' % (err, '; '.join(last.get('why', [])))) from None
