"""swarm_controller: one rospy node driving every robot of a Stage swarm by expand_swarm's law."""
import threading
import time

import rosgraph
import rospy
from course_common.param_loader import load_or_exit
from course_common.publishers import unqueued_publisher
from course_common.rospy_internals import (
    one_receive_thread,
    shutdown_requested,
    throttled_topic_checks,
)
from course_common.schedule import BAD_INPUT_WARN_PERIOD_S
from course_common.startup import init_node, loop_at_rate, quiet_at_shutdown
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from . import expand_law
from .robot_topics import driven_robots, first_few, missing_robots, robot_topics, scan_robots
from .spread import spread_m
from .swarm_params import load_params

#: Wall s between looks at the master while waiting for stageros's robots
POLL_S = 0.5
#: queue_size of every subscription: only the newest scan and odom matter to a law that reads
#: the latest reading
QUEUE_SIZE = 1


class SwarmController:
    """Drives robots first..first+N-1 of stageros by Stage's expand_swarm law, from one node.

    Subscribes: /robot_<i>/base_scan (sensor_msgs/LaserScan), /robot_<i>/odom
        (nav_msgs/Odometry), for each robot i driven (with one robot in the world: base_scan,
        odom, relative);
        queue 1 each, all read by one thread (rospy_internals.one_receive_thread; rospy
        alone gives each connection a thread: 2 per robot).
    Publishes: /robot_<i>/cmd_vel (geometry_msgs/Twist, no send queue) for each robot with
        a scan, at ~rate_hz of sim time (/use_sim_time: stageros's clock); one zero Twist
        each at shutdown. A scan with a NaN or negative range: a zero Twist (and a throttled WARN).
    Services: none.
    Parameters (private):
        ~robots (int, 0): how many robots; 0: as many as stageros publishes scans for (the
            master's /robot_<i>/base_scan topics, once their count holds for ~discover_s),
            from ~first on.
        ~first (int, 0): the first robot driven: nodes on several hosts split a swarm.
        ~rate_hz (float, 10, Hz of sim time): commands per second (stageros steps at 10).
        ~laser_yaw_deg (float, 165, degrees): the laser's yaw on the robot (the swarm
            world's ring: beam i looks along 30 i degrees).
        ~discover_s (float, 1.0, wall s): how long the discovered count must hold.
        ~report_period_s (float, 10, sim s): between status lines (spread of the swarm).
        ~first_scan_warn_s (float, 30, wall s): then a WARN names the robots without a scan.
    """

    def __init__(self, ids, naming_count, params):
        """ids: the robot numbers driven (a range); naming_count: how many robots stageros
        has, as far as names go (one robot: relative names)."""
        self.ids = ids
        self.count = count = len(ids)
        self.params = params
        self._lock = threading.Lock()       # the latest readings and the plans
        self._scans = [None] * count        # the latest LaserScan of each robot
        self._poses = [None] * count        # the latest (x, y) from odom
        self._plans = {}                    # scan geometry -> expand_law.RingPlan
        self._warned = {}                   # what was warned -> wall time
        self._started = time.monotonic()
        self._all_scanned = False
        self._stopped = False
        self._last_report = None
        self.topics = [robot_topics(i, naming_count) for i in ids]
        # no send queue (rospy's queue_size=None): a queue is a thread per connection, 1,000
        # more threads at 1,000 robots; the tick writes each command itself, which is the same
        # message on the wire
        self._pubs = [unqueued_publisher(t.cmd_vel, Twist) for t in self.topics]
        # subscribed last: the callbacks may run at once
        self._subs = []
        for i, t in enumerate(self.topics):
            self._subs.append(rospy.Subscriber(t.scan, LaserScan, self._on_scan, i,
                                               queue_size=QUEUE_SIZE))
            self._subs.append(rospy.Subscriber(t.odom, Odometry, self._on_odom, i,
                                               queue_size=QUEUE_SIZE))

    def _on_scan(self, msg, index):
        with self._lock:
            self._scans[index] = msg

    def _on_odom(self, msg, index):
        p = msg.pose.pose.position
        with self._lock:
            self._poses[index] = (p.x, p.y)

    def _warn(self, key, text, *args):
        now = time.monotonic()
        if now - self._warned.get(key, -1e9) >= BAD_INPUT_WARN_PERIOD_S:
            self._warned[key] = now
            rospy.logwarn(text, *args)

    def _plan(self, scan):
        key = (scan.angle_min, scan.angle_increment, len(scan.ranges))
        plan = self._plans.get(key)
        if plan is None:
            plan = self._plans[key] = expand_law.ring_plan(
                scan.angle_min, scan.angle_increment, len(scan.ranges),
                self.params.laser_yaw_rad)
        return plan

    def command_of(self, index, scan):
        """The Twist for robot `index` from its scan, or None (the law sets nothing, or the
        scan's geometry is not the ring: a WARN)."""
        try:
            plan = self._plan(scan)
        except ValueError as err:
            self._warn(('geometry', index), 'swarm: %s: %s', self.topics[index].scan, err)
            return None
        try:
            ranges = expand_law.clean_ranges(scan.ranges, scan.range_max)
        except ValueError as err:
            self._warn(('ranges', index), 'swarm: %s: %s: stopping robot_%d',
                       self.topics[index].scan, err, self.ids[index])
            return Twist()
        out = expand_law.command(plan, ranges)
        if out is None:
            return None
        twist = Twist()
        twist.linear.x, twist.angular.z = out
        return twist

    def tick(self):
        """One control cycle: a command for every robot that has sent a scan."""
        with self._lock:
            scans = list(self._scans)
        for i, scan in enumerate(scans):
            if scan is None:
                continue
            twist = self.command_of(i, scan)
            if twist is not None and not self._stopped:
                self._pubs[i].publish(twist)
        self._watch_start(scans)
        self._report()

    def _watch_start(self, scans):
        if self._all_scanned:
            return
        waiting = [self.ids[k] for k, s in enumerate(scans) if s is None]
        if not waiting:
            self._all_scanned = True
            rospy.loginfo("swarm: every robot's first scan received: %d robots, %.2f s after "
                          'the node started', self.count, time.monotonic() - self._started)
        elif time.monotonic() - self._started > self.params.first_scan_warn_s:
            self._warn('first scans', 'swarm: no scan yet from %s: is stageros running a '
                       'world with that many robots?', first_few(waiting))

    def _report(self):
        now = rospy.get_time()
        if self._last_report is not None and now - self._last_report < self.params.report_period_s:
            return
        self._last_report = now
        with self._lock:
            poses = [p for p in self._poses if p is not None]
        if poses:
            rospy.loginfo('swarm: t = %.1f s, %d robots with odometry, spread %.2f m',
                          now, len(poses), spread_m(poses))

    def run(self):
        """Ticks at ~rate_hz of sim time until shutdown; a restarted stageros sends /clock
        back and rospy's Rate gives up (ROSTimeMovedBackwardsException): start again."""
        while not shutdown_requested():
            loop_at_rate(self.params.rate_hz, self.tick)

    def stop(self):
        """A zero Twist to every robot (rospy.on_shutdown)."""
        self._stopped = True
        for pub in self._pubs:
            quiet_at_shutdown(pub.publish)(Twist())


def published_topics():
    """The master's published topic names ([] when it cannot be reached)."""
    try:
        return [t for t, _ in rosgraph.Master(rospy.get_name()).getPublishedTopics('/')]
    except (OSError, rosgraph.MasterError):
        return []


def discover_count(hold_s):
    """How many robots stageros publishes scans for, once the count has held for hold_s
    (stageros registers its topics one by one); waits, with a WARN now and then, for a
    stageros that has not started; 0 at shutdown."""
    last, since, warned = None, time.monotonic(), time.monotonic()
    while not shutdown_requested():
        found = scan_robots(published_topics())
        count = len(found)
        now = time.monotonic()
        if count != last:
            last, since = count, now
        elif count and now - since >= hold_s:
            gaps = missing_robots(found, range(found[-1] + 1))
            if gaps:
                rospy.logwarn('swarm: robots numbered up to %d but no scan topic for %s',
                              found[-1], first_few(gaps))
            return found[-1] + 1
        if not count and now - warned >= BAD_INPUT_WARN_PERIOD_S * 2:
            warned = now
            rospy.logwarn('swarm: waiting for stageros: no /robot_<i>/base_scan on the '
                          'master yet')
        time.sleep(POLL_S)
    return 0


def check_ids(ids):
    """WARN if the master lists no scan for some robots driven, or (a node driving from
    robot_0) scans of more robots than it drives."""
    found = scan_robots(published_topics())
    missing = missing_robots(found, ids)
    if found and missing:
        rospy.logwarn('swarm: told to drive robot_%d to robot_%d but stageros publishes no '
                      'scan for %s: those robots stay still until it does', ids[0], ids[-1],
                      first_few(missing))
    if found and found[-1] >= ids.stop and ids.start == 0:
        rospy.logwarn('swarm: ~robots is %d but stageros has %d robots: robot_%d and after '
                      'are not driven', len(ids), found[-1] + 1, ids.stop)


def discover_ids(params):
    """The robots to drive, from ~first to the last one stageros has (waits for stageros,
    WARNs while ~first is past its last robot); None at shutdown."""
    while not shutdown_requested():
        count = discover_count(params.discover_s)
        if count == 0:
            return None
        try:
            return driven_robots(params.first, 0, count), count
        except ValueError as err:
            rospy.logwarn_throttle(BAD_INPUT_WARN_PERIOD_S * 10, 'swarm: %s: waiting for more '
                                   'robots' % err)
        time.sleep(POLL_S)
    return None


def main():
    throttled_topic_checks()  # 3 topics a robot: rospy's checks after each registration
    one_receive_thread()      # 2 subscribed connections a robot: one thread, not 2 N
    init_node('swarm_controller')
    params = load_or_exit(load_params, 'swarm_controller')
    if not rospy.get_param('/use_sim_time', False):
        rospy.logwarn('swarm: /use_sim_time was not true when this node started: commands '
                      'are paced by the wall clock, not by stageros (set it before starting '
                      'the node: stageros sets it only once it runs, stage_ros #49)')
    if params.robots == 0:
        found = discover_ids(params)
        if found is None:
            return
        ids, naming_count = found
    else:
        ids = driven_robots(params.first, params.robots)
        naming_count = ids.stop
        check_ids(ids)
    node = SwarmController(ids, naming_count, params)
    rospy.on_shutdown(node.stop)
    rospy.loginfo('swarm: driving %d robots (robot_%d to robot_%d) by expand_swarm at %g Hz of '
                  'sim time, laser yaw %.1f deg', len(ids), ids[0], ids[-1], params.rate_hz,
                  params.laser_yaw_rad * 57.29577951308232)
    threading.Thread(target=node.run, name='swarm_ticks', daemon=True).start()
    rospy.spin()
