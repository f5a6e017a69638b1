"""The lesson's monitor: counts ready robots on team_status and broadcasts GO."""
import threading
import time

import rospy
from course_common.command_line import parse_argv_or_exit
from course_common.publishers import LostSubscribers, OnNewSubscriber, unqueued_publisher
from course_common.robot_ids import parse_team_size
from course_common.rospy_internals import caller_id, connection_ids
from course_common.startup import init_node, quiet_at_shutdown

from multi_sync.go_latch import GoLatch
from multi_sync.msg import RobotStatus
from multi_sync.team import MONITOR_FRAME_ID, Outcome, TeamBook

# Robots re-announce every second until GO; a backlog this deep absorbs a whole team's
# announcements (20 robots, several rounds) without dropping one.
STATUS_QUEUE = 100
# A freshly started monitor hears the robots (it connects to their publishers) before the
# robots have connected to its own publisher. GO waits until every ready robot listens, so
# all receive the same GO message at once, and on sim time until the first /clock (else its
# stamp would read 0), but no longer than this, in wall seconds (a robot that subscribes
# later gets GO as it connects).
CONNECT_WAIT_S = 3.0
# GO goes out no sooner than this after the ready that completed the team (wall clock). That
# ready went from its robot to every teammate over connections of its own, not the monitor's:
# a GO sent at once can overtake it, and a robot whose queue holds one message (the lesson's
# C++ robot: queue 1, spinOnce at 1 Hz) then reads the teammate's ready in place of GO and
# waits forever. Half a second covers a loaded machine's delivery many times over and
# is less than the lesson robot's own 1 s loop.
READY_SETTLE_S = 0.5
# How often a pending GO checks its conditions and the deadline above (wall clock).
CHECK_PERIOD_S = 0.05


class MonitorNode:
    """Waits until team_size distinct robots are ready, then publishes GO.

    Subscribes:
        team_status (multi_sync/RobotStatus): robots' ready reports; messages whose
            header.frame_id is "monitor" (its own GO) are ignored, ids outside 0..19 are
            ignored with a warning, duplicates are counted once.
    Publishes:
        team_status (multi_sync/RobotStatus): GO, header.stamp = now,
            header.frame_id = "monitor", robot_id = -1, is_ready = true. It is sent once
            every ready robot has subscribed and, on sim time, the clock runs (at most
            CONNECT_WAIT_S after the last ready),
            no sooner than READY_SETTLE_S after the last ready (so that every teammate has
            that ready before GO, whatever its queue size), to every subscriber in one pass,
            and to each later subscriber as it connects:
            every subscriber gets exactly one GO (multi_sync.go_latch says why this is not
            rospy's latch). A ready report after GO is logged and not answered.
            A subscriber the master lists that never connected (a lost connection on a
            loaded machine: it would never hear GO) gets the publisher registered again.
    Services: none.
    Parameters: none (the team size is argv[1], as in the lesson).
    """

    def __init__(self, team_size):
        self._book = TeamBook(team_size)
        self._latch = GoLatch()
        self._lock = threading.Lock()
        self._go_deadline = None  # set while GO waits for robots to subscribe
        self._go_not_before = 0.0  # the last ready's arrival + READY_SETTLE_S (monotonic)
        # Synchronous: GO goes out to every robot from this thread in one pass.
        self._pub = unqueued_publisher('team_status', RobotStatus,
                                       subscriber_listener=OnNewSubscriber(self._on_subscriber))
        # A robot whose connection to this publisher was lost would wait for GO for ever.
        self._lost = LostSubscribers(self._pub, describe='monitor: %s')
        threading.Thread(target=quiet_at_shutdown(self._heal_connections), name='heal',
                         daemon=True).start()
        rospy.loginfo('Waiting for robots to connect...')
        self._sub = rospy.Subscriber('team_status', RobotStatus, self._on_status,
                                     queue_size=STATUS_QUEUE, tcp_nodelay=True)

    def _on_subscriber(self, send):
        """A new subscriber connection: GO now if it was given, else maybe it completes GO."""
        with self._lock:
            if self._latch.connected(send):
                send(self._latch.message)
                return
        self._try_go()

    def _publish_go(self):
        go = RobotStatus()
        go.header.stamp = rospy.Time.now()
        go.header.frame_id = MONITOR_FRAME_ID
        go.robot_id = -1
        go.is_ready = True
        for send in self._latch.give(go):
            send(go)

    def _try_go(self, force=False):
        """Publish the pending GO once the last ready has settled, every ready robot listens
        and the clock runs (or force); log it. Returns False while GO is still pending."""
        with self._lock:
            if self._go_deadline is None:
                return True
            if time.monotonic() < self._go_not_before:  # even when forced: never overtake
                return False
            missing = self._book.unconnected(connection_ids(self._pub))
            # Zero only on sim time before the first /clock.
            no_clock = rospy.get_rostime().is_zero()
            if (missing or no_clock) and not force:
                return False
            self._go_deadline = None
            # Publish first, log after: robots start on this message.
            self._publish_go()
        rospy.loginfo('All robots GO!')
        if missing:
            rospy.logwarn('GO sent before robot(s) %s subscribed to %s: they get it when they do'
                          % (', '.join(map(str, missing)), self._pub.resolved_name))
        if no_clock:
            rospy.logwarn('GO sent before the first /clock (use_sim_time is set): stamped 0')
        return True

    def _go_when_ready(self):
        """Until the pending GO is out: try every CHECK_PERIOD_S, force it at the deadline.

        A thread on the wall clock: connections come up in wall time, and on sim time a
        rospy.Timer would not run before the first /clock.
        """
        while not rospy.is_shutdown():
            with self._lock:
                deadline = self._go_deadline
            if deadline is None or self._try_go(force=time.monotonic() >= deadline):
                return
            time.sleep(CHECK_PERIOD_S)

    def _heal_connections(self):
        """For the node's life: subscribers lost to team_status get it registered again.
        A thread on the wall clock: on sim time a rospy.Timer waits for the first /clock."""
        while not rospy.is_shutdown():
            time.sleep(self._lost.period_s)   # check() asks the master at most this often
            self._lost.check()

    def _on_status(self, msg):
        sender = caller_id(msg)
        with self._lock:
            outcome = self._book.report(msg.robot_id, msg.is_ready, msg.header.frame_id, sender)
            if outcome is Outcome.TEAM_READY:
                now = time.monotonic()
                self._go_not_before = now + READY_SETTLE_S
                self._go_deadline = now + CONNECT_WAIT_S
            elif outcome is Outcome.AFTER_GO and self._go_deadline is not None:
                # GO is pending (settling, or waiting for connections): a robot re-announcing
                # is not late yet, and "after GO" would come before "All robots GO!".
                outcome = Outcome.DUPLICATE
        if outcome in (Outcome.NEW_READY, Outcome.TEAM_READY):
            rospy.loginfo('Robot %d is ready!', msg.robot_id)
        if outcome is Outcome.TEAM_READY:
            threading.Thread(target=quiet_at_shutdown(self._go_when_ready), name='go_when_ready',
                             daemon=True).start()
        elif outcome is Outcome.AFTER_GO:
            rospy.loginfo_throttle_identical(
                5.0, 'Robot %d reported ready after GO: it gets GO as it subscribes, not again'
                % msg.robot_id)
        elif outcome is Outcome.BAD_ID:
            rospy.logwarn_throttle(
                5.0, 'Ignoring status with robot_id %d: expected an id between 0 and 19'
                % msg.robot_id)
        elif outcome is Outcome.NOT_READY:
            rospy.logdebug('Robot %d reported not ready: ignored', msg.robot_id)


def main(argv=None):
    """rosrun multi_sync monitor TEAM_SIZE."""
    team_size = parse_argv_or_exit(parse_team_size, argv)
    init_node('monitor')
    MonitorNode(team_size)
    rospy.spin()
