"""pose_to_tf: every turtle of the graph in tf, parent `world`, child the turtle's name."""

import threading
from dataclasses import dataclass

import rospy
import tf2_ros
from course_common.param_loader import get_private, load_or_exit
from course_common.params import check_name_list, check_number
from course_common.startup import init_node, quiet_at_shutdown
from geometry_msgs.msg import TransformStamped

from turtle_lite.pose_watch import PoseWatch, WatchParams, load_watch_params
from turtle_lite.team_frames import pose_to_transform

WARN_PERIOD_S = 5.0


@dataclass(frozen=True)
class PoseToTfConfig:
    """pose_to_tf's parameters, validated."""

    watch: WatchParams
    turtles: tuple
    rate_hz: float


def load_config():
    """Reads and validates the private parameters. Raises ParamError naming the bad one."""
    return PoseToTfConfig(
        watch=load_watch_params(),
        turtles=check_name_list('~turtles', get_private('turtles', [])),
        rate_hz=check_number('~rate_hz', get_private('rate_hz', 62.5), low=0.0))


def transform_msg(parent, child, stamp, transform):
    """A geometry_msgs/TransformStamped from a team_frames.Transform."""
    msg = TransformStamped()
    msg.header.stamp = stamp
    msg.header.frame_id = parent
    msg.child_frame_id = child
    t = msg.transform
    t.translation.x, t.translation.y, t.translation.z = transform.x, transform.y, transform.z
    t.rotation.x, t.rotation.y = transform.qx, transform.qy
    t.rotation.z, t.rotation.w = transform.qz, transform.qw
    return msg


class PoseToTf:
    """Broadcasts world -> <turtle> for every turtle whose pose topic is on the master.

    Subscribes:
        <turtle>/pose (turtlesim/Pose, queue 1) for every turtlesim/Pose topic below
            ~namespace, found by asking the master every ~discovery_period_s: spawned turtles
            join, killed ones leave, whichever simulator or node made them.
    Publishes:
        /tf (tf2_msgs/TFMessage, through tf2_ros): parent ~parent_frame, child the turtle's
            name relative to ~namespace (turtle1, robot1, turtlesim1/turtle1), translation
            (x, y, 0) m, rotation the yaw theta; stamped with the pose's arrival time.
    Parameters:
        ~parent_frame (str, "world"), ~namespace (str, "/": every simulator),
        ~turtles (list of str, []: all; else only these frames),
        ~discovery_period_s (float > 0, 0.5 s),
        ~rate_hz (float >= 0, 62.5 Hz, the pose rate): all turtles' new transforms go out in
            one message per tick; 0 sends one message per pose as it arrives (the tf2
            tutorial's broadcaster).
    """

    def __init__(self, config):
        self._config = config
        self._broadcaster = tf2_ros.TransformBroadcaster()
        self._lock = threading.Lock()
        self._pending = {}  # frame -> TransformStamped not yet sent (batched mode)
        self._timer = None
        if config.rate_hz > 0:
            self._timer = rospy.Timer(rospy.Duration(1.0 / config.rate_hz),
                                      quiet_at_shutdown(self._flush))
        self._watch = PoseWatch(config.watch, config.turtles, self._on_pose, self._on_gone)

    def _on_pose(self, frame, msg, stamp):
        try:
            transform = pose_to_transform(msg.x, msg.y, msg.theta)
        except ValueError as err:
            rospy.logwarn_throttle(WARN_PERIOD_S, 'pose_to_tf: ignoring %s: %s', frame, err)
            return
        tf_msg = transform_msg(self._config.watch.parent_frame, frame, stamp, transform)
        if self._timer is None:
            self._broadcaster.sendTransform(tf_msg)
        else:
            with self._lock:
                self._pending[frame] = tf_msg

    def _on_gone(self, frame):
        with self._lock:
            self._pending.pop(frame, None)

    def _flush(self, _event):
        with self._lock:
            batch, self._pending = list(self._pending.values()), {}
        if batch:
            # One TFMessage for the whole team: one serialisation and one write per listener.
            self._broadcaster.sendTransform(batch)

    def shutdown(self):
        self._watch.shutdown()
        if self._timer is not None:
            self._timer.shutdown()


def main():
    init_node('pose_to_tf')
    config = load_or_exit(load_config, 'pose_to_tf')
    rospy.loginfo('pose_to_tf: %s -> every turtle below %s%s, %s', config.watch.parent_frame,
                  config.watch.namespace,
                  ' (only %s)' % ', '.join(config.turtles) if config.turtles else '',
                  'batched at %g Hz' % config.rate_hz if config.rate_hz else 'one per pose')
    node = PoseToTf(config)
    rospy.on_shutdown(node.shutdown)
    rospy.spin()
