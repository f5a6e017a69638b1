"""convoy_gaps: each follower's distance to its leader, as rviz text markers."""

import threading
from dataclasses import dataclass

import rospy
from course_common.param_loader import get_private, load_or_exit
from course_common.params import ParamError, check_name, check_number
from course_common.startup import init_node, quiet_at_shutdown
from geometry_msgs.msg import Point
from std_msgs.msg import ColorRGBA
from turtlesim.msg import Pose
from visualization_msgs.msg import Marker, MarkerArray

from convoy.gap_labels import chain_links, gap_label

DEFAULT_ROBOTS = ['robot1', 'robot2', 'robot3']  # the course's convoy.launch
TEXT_HEIGHT_M = 0.3
# Below the midpoint: lesson_markers writes the robots' names above them.
TEXT_OFFSET_Y_M = -0.35
LINE_WIDTH_M = 0.03
TEXT_RGBA = (1.0, 1.0, 1.0, 1.0)
LINE_RGBA = (1.0, 1.0, 1.0, 0.5)
WARN_PERIOD_S = 5.0


@dataclass(frozen=True)
class ConvoyGapsConfig:
    """convoy_gaps' parameters, validated."""

    links: tuple
    parent_frame: str
    rate_hz: float


def load_config():
    """Reads and validates the private parameters. Raises ParamError naming the bad one."""
    robots = get_private('robots', DEFAULT_ROBOTS)
    try:
        links = tuple(chain_links(robots))
    except ValueError as err:
        raise ParamError('~robots', robots, str(err)) from err
    return ConvoyGapsConfig(
        links=links,
        parent_frame=check_name('~parent_frame', get_private('parent_frame', 'world')),
        rate_hz=check_number('~rate_hz', get_private('rate_hz', 5.0), low=0.0, low_open=True))


class ConvoyGaps:
    """Publishes, for each follower, its gap to its leader where rviz shows it.

    Subscribes:
        <robot>/pose (turtlesim/Pose, queue 1) for each robot of ~robots.
    Publishes:
        convoy_gaps (visualization_msgs/MarkerArray, every 1/~rate_hz s): per follower, in
            ~parent_frame, namespace "gap" a text "robot2 -> robot1 1.73 m" at the midpoint
            and namespace "link" a line from follower to leader. Nothing for a pair until both
            poses have arrived.
    Parameters:
        ~robots (list of str, [robot1, robot2, robot3]): the convoy, leader first; each robot
            follows the one before it, as convoy.launch and convoy_chain.launch wire them.
        ~parent_frame (str, "world"), ~rate_hz (float > 0, 5 Hz).
    """

    def __init__(self, config):
        self._config = config
        self._lock = threading.Lock()
        self._xy = {}
        self._pub = rospy.Publisher('convoy_gaps', MarkerArray, queue_size=1)
        robots = sorted({r for link in config.links for r in link})
        self._subs = [rospy.Subscriber(r + '/pose', Pose, self._on_pose, callback_args=r,
                                       queue_size=1) for r in robots]
        self._timer = rospy.Timer(rospy.Duration(1.0 / config.rate_hz),
                                  quiet_at_shutdown(self._publish))

    def _on_pose(self, msg, robot):
        with self._lock:
            self._xy[robot] = (msg.x, msg.y)

    def _marker(self, ns, marker_id, kind, rgba):
        m = Marker()
        m.header.frame_id = self._config.parent_frame
        m.header.stamp = rospy.Time.now()
        m.ns, m.id, m.type, m.action = ns, marker_id, kind, Marker.ADD
        m.pose.orientation.w = 1.0
        m.color = ColorRGBA(*rgba)
        return m

    def _publish(self, _event):
        with self._lock:
            xy = dict(self._xy)
        out = MarkerArray()
        for marker_id, (follower, leader) in enumerate(self._config.links):
            if follower not in xy or leader not in xy:
                continue
            try:
                label = gap_label(follower, leader, xy[follower], xy[leader])
            except ValueError as err:
                rospy.logwarn_throttle(WARN_PERIOD_S, 'convoy_gaps: %s', err)
                continue
            text = self._marker('gap', marker_id, Marker.TEXT_VIEW_FACING, TEXT_RGBA)
            text.pose.position.x, text.pose.position.y = label.mid_x, label.mid_y + TEXT_OFFSET_Y_M
            text.scale.z = TEXT_HEIGHT_M
            text.text = label.text
            link = self._marker('link', marker_id, Marker.LINE_LIST, LINE_RGBA)
            link.scale.x = LINE_WIDTH_M
            link.points = [Point(*xy[follower], 0.0), Point(*xy[leader], 0.0)]
            out.markers.extend((text, link))
        if out.markers:
            self._pub.publish(out)


def main():
    init_node('convoy_gaps')
    config = load_or_exit(load_config, 'convoy_gaps')
    rospy.loginfo('convoy_gaps: %s', ', '.join('%s -> %s' % link for link in config.links))
    ConvoyGaps(config)
    rospy.spin()
