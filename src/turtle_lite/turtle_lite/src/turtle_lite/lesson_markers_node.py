"""lesson_markers: what rviz shows of a lesson: the arena, each robot's arrow, name and trail."""

import threading
from dataclasses import dataclass

import rospy
from course_common.arena import arena_outline
from course_common.param_loader import get_private, load_or_exit
from course_common.params import check_int, check_number
from course_common.rviz.colours import ARENA_RGB, robot_color
from course_common.startup import init_node, quiet_at_shutdown
from course_common.trail import Trail
from geometry_msgs.msg import Point
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

from turtle_lite.pose_watch import PoseWatch, WatchParams, load_watch_params

LINE_WIDTH_M = 0.05
ARROW_SIZE_M = (0.8, 0.15, 0.15)  # length, shaft and head diameter: a turtle is about 0.5 m
TEXT_HEIGHT_M = 0.35
LABEL_OFFSET_M = 0.55  # the name sits beside the arrow, not on it
WARN_PERIOD_S = 5.0


@dataclass(frozen=True)
class LessonMarkersConfig:
    """lesson_markers' parameters, validated."""

    watch: WatchParams
    trail_points: int
    trail_spacing_m: float
    rate_hz: float


def load_config():
    """Reads and validates the private parameters. Raises ParamError naming the bad one."""
    return LessonMarkersConfig(
        watch=load_watch_params(),
        trail_points=check_int(
            '~trail_points', get_private('trail_points', 600), low=2, high=100000),
        trail_spacing_m=check_number(
            '~trail_spacing_m', get_private('trail_spacing_m', 0.05), low=0.0),
        rate_hz=check_number('~rate_hz', get_private('rate_hz', 5.0), low=0.0, low_open=True))


def _color(rgb, alpha=1.0):
    return ColorRGBA(rgb[0], rgb[1], rgb[2], alpha)


def _marker(ns, marker_id, frame, kind):
    m = Marker()
    m.header.frame_id = frame
    m.header.stamp = rospy.Time(0)  # the newest tf: no extrapolation against a moving robot
    m.ns = ns
    m.id = marker_id
    m.type = kind
    m.action = Marker.ADD
    m.pose.orientation.w = 1.0
    return m


class LessonMarkers:
    """Publishes the lesson's markers for rviz, for every turtle on the master.

    Subscribes:
        <turtle>/pose (turtlesim/Pose, queue 1) for every turtlesim/Pose topic below
            ~namespace (spawned turtles join, killed ones leave, as in pose_to_tf).
    Publishes:
        lesson_markers (visualization_msgs/MarkerArray, every 1/~rate_hz s): namespace "arena"
            the 11.09 m square (line strip in ~parent_frame); per robot, "robot" an arrow and
            "name" its name, both in the robot's own tf frame (frame_locked: rviz places them
            through tf, so pose_to_tf must run), and "trail" its last ~trail_points positions
            in ~parent_frame. A robot that leaves gets DELETE markers.
    Parameters:
        ~parent_frame (str, "world"), ~namespace (str, "/"), ~trail_points (int 2..100000,
        600), ~trail_spacing_m (float >= 0, 0.05 m: 30 m of trail by default),
        ~rate_hz (float > 0, 5 Hz), ~discovery_period_s (float > 0, 0.5 s).
    """

    def __init__(self, config):
        self._config = config
        self._lock = threading.Lock()
        self._robots = {}  # frame -> (marker id, Trail)
        self._next_id = 0
        self._deleted = []
        self._pub = rospy.Publisher('lesson_markers', MarkerArray, queue_size=1)
        self._arena = self._arena_marker()
        self._watch = PoseWatch(config.watch, (), self._on_pose, self._on_gone)
        self._timer = rospy.Timer(rospy.Duration(1.0 / config.rate_hz),
                                  quiet_at_shutdown(self._publish))

    def _arena_marker(self):
        m = _marker('arena', 0, self._config.watch.parent_frame, Marker.LINE_STRIP)
        m.scale.x = LINE_WIDTH_M
        m.color = _color(ARENA_RGB)
        m.points = [Point(x, y, 0.0) for x, y in arena_outline()]
        return m

    def _on_pose(self, frame, msg, _stamp):
        with self._lock:
            robot = self._robots.get(frame)
            if robot is None:
                robot = self._robots[frame] = (self._next_id, Trail(
                    self._config.trail_points, self._config.trail_spacing_m))
                self._next_id += 1
            try:
                robot[1].add(msg.x, msg.y)
            except ValueError as err:
                rospy.logwarn_throttle(WARN_PERIOD_S, 'lesson_markers: %s: %s', frame, err)

    def _on_gone(self, frame):
        with self._lock:
            robot = self._robots.pop(frame, None)
            if robot is not None:
                self._deleted.append(robot[0])

    def _robot_markers(self, frame, marker_id, trail_points):
        rgb = robot_color(marker_id)
        arrow = _marker('robot', marker_id, frame, Marker.ARROW)
        arrow.frame_locked = True
        arrow.scale.x, arrow.scale.y, arrow.scale.z = ARROW_SIZE_M
        arrow.color = _color(rgb)
        name = _marker('name', marker_id, frame, Marker.TEXT_VIEW_FACING)
        name.frame_locked = True
        name.pose.position.y = LABEL_OFFSET_M
        name.scale.z = TEXT_HEIGHT_M
        name.color = _color((1.0, 1.0, 1.0))
        name.text = frame
        markers = [arrow, name]
        if len(trail_points) >= 2:  # a line strip needs two points
            trail = _marker('trail', marker_id, self._config.watch.parent_frame, Marker.LINE_STRIP)
            trail.scale.x = LINE_WIDTH_M
            trail.color = _color(rgb, 0.8)
            trail.points = [Point(x, y, 0.0) for x, y in trail_points]
            markers.append(trail)
        return markers

    def _publish(self, _event):
        with self._lock:
            robots = [(frame, mid, trail.points()) for frame, (mid, trail) in self._robots.items()]
            deleted, self._deleted = self._deleted, []
        out = MarkerArray()
        out.markers.append(self._arena)
        for frame, marker_id, points in sorted(robots):
            out.markers.extend(self._robot_markers(frame, marker_id, points))
        for marker_id in deleted:
            for ns in ('robot', 'name', 'trail'):
                gone = _marker(ns, marker_id, self._config.watch.parent_frame, Marker.ARROW)
                gone.action = Marker.DELETE
                out.markers.append(gone)
        self._pub.publish(out)

    def shutdown(self):
        self._timer.shutdown()
        self._watch.shutdown()


def main():
    init_node('lesson_markers')
    config = load_or_exit(load_config, 'lesson_markers')
    rospy.loginfo('lesson_markers: arena, arrows and trails (%d points) in %s at %g Hz',
                  config.trail_points, config.watch.parent_frame, config.rate_hz)
    node = LessonMarkers(config)
    rospy.on_shutdown(node.shutdown)
    rospy.spin()
