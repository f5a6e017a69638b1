"""The lesson's monitor: counts ready robots on team_status and broadcasts GO."""
import threading

import rospy
from course_common.rospy_internals import caller_id, connection_ids

from multi_sync.msg import RobotStatus
from multi_sync.node_util import parse_argv_or_exit, synchronous_publisher
from multi_sync.team import MONITOR_FRAME_ID, Outcome, TeamBook, parse_team_size

# Robots re-announce every second until GO; a backlog this deep absorbs a whole team's
# announcements (20 robots, several rounds) without dropping one.
STATUS_QUEUE = 100
# A freshly started monitor hears the robots (it connects to their publishers) before the
# robots have connected to its own publisher. GO waits until every ready robot listens, so
# all receive the same GO message at once, but no longer than this (the GO is latched, and
# a robot that still reports ready afterwards is answered).
CONNECT_WAIT_S = 3.0
# How often a pending GO re-checks the deadline above.
CHECK_PERIOD_S = 0.05


class _RecheckOnConnect(rospy.SubscribeListener):
    """Calls back whenever a node subscribes to the monitor's team_status publisher."""

    def __init__(self, callback):
        super().__init__()
        self._callback = callback

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        self._callback()


class MonitorNode:
    """Waits until team_size distinct robots are ready, then publishes GO.

    Subscribes:
        team_status (multi_sync/RobotStatus): robots' ready reports; messages whose
            header.frame_id is "monitor" (its own GO) are ignored, ids outside 0..19 are
            ignored with a warning, duplicates are counted once.
    Publishes:
        team_status (multi_sync/RobotStatus, latched): GO, header.stamp = now,
            header.frame_id = "monitor", robot_id = -1, is_ready = true. It is sent once
            every ready robot has subscribed (at most CONNECT_WAIT_S after the last ready).
            Latched, so a robot that subscribes after GO receives it on connecting; a ready
            report after GO from a node GO did not reach (a robot started late) is answered
            with a fresh GO.
    Services: none.
    Parameters: none (the team size is argv[1], as in the lesson).
    """

    def __init__(self, team_size):
        self._book = TeamBook(team_size)
        self._lock = threading.Lock()
        self._go_deadline = None  # set while GO waits for robots to subscribe
        # Synchronous: GO goes out to every robot from this thread in one pass.
        self._pub = synchronous_publisher('team_status', RobotStatus, latch=True,
                                          subscriber_listener=_RecheckOnConnect(self._try_go))
        self._timer = rospy.Timer(rospy.Duration(CHECK_PERIOD_S), self._on_timer)
        rospy.loginfo('Waiting for robots to connect...')
        self._sub = rospy.Subscriber('team_status', RobotStatus, self._on_status,
                                     queue_size=STATUS_QUEUE, tcp_nodelay=True)

    def _publish_go(self):
        go = RobotStatus()
        go.header.stamp = rospy.Time.now()
        go.header.frame_id = MONITOR_FRAME_ID
        go.robot_id = -1
        go.is_ready = True
        self._pub.publish(go)
        # Read after publishing: a node that connected meanwhile got the latched GO instead.
        self._book.go_sent(connection_ids(self._pub))

    def _try_go(self, force=False):
        """Publish the pending GO if every ready robot listens (or force); log it."""
        with self._lock:
            if self._go_deadline is None:
                return
            missing = self._book.unconnected(connection_ids(self._pub))
            if missing and not force:
                return
            self._go_deadline = None
            # Publish first, log after: robots start on this message.
            self._publish_go()
        rospy.loginfo('All robots GO!')
        if missing:
            rospy.logwarn('GO sent before robot(s) %s subscribed to %s: they get it when they do'
                          % (', '.join(map(str, missing)), self._pub.resolved_name))

    def _on_timer(self, _event):
        with self._lock:
            late = self._go_deadline is not None and rospy.get_time() > self._go_deadline
        if late:
            self._try_go(force=True)

    def _on_status(self, msg):
        sender = caller_id(msg)
        with self._lock:
            outcome = self._book.report(msg.robot_id, msg.is_ready, msg.header.frame_id, sender)
            if outcome is Outcome.TEAM_READY:
                self._go_deadline = rospy.get_time() + CONNECT_WAIT_S
            answer = outcome is Outcome.ANSWER_GO and self._go_deadline is None
            if answer:
                self._publish_go()
        if outcome in (Outcome.NEW_READY, Outcome.TEAM_READY):
            rospy.loginfo('Robot %d is ready!', msg.robot_id)
        if outcome is Outcome.TEAM_READY:
            self._try_go()
        elif answer:
            rospy.loginfo('Robot %d reported ready after GO: sent GO again', msg.robot_id)
        elif outcome is Outcome.BAD_ID:
            rospy.logwarn_throttle(
                5.0, 'Ignoring status with robot_id %d: expected an id between 0 and 19'
                % msg.robot_id)
        elif outcome is Outcome.GO_ON_ITS_WAY:
            rospy.logdebug('Robot %d reported ready while GO was on its way to it: not repeated',
                           msg.robot_id)
        elif outcome is Outcome.NOT_READY:
            rospy.logdebug('Robot %d reported not ready: ignored', msg.robot_id)


def main(argv=None):
    """rosrun multi_sync monitor TEAM_SIZE."""
    team_size = parse_argv_or_exit(parse_team_size, argv)
    rospy.init_node('monitor')
    MonitorNode(team_size)
    rospy.spin()
