"""What move_robot knows of its robot, from turtlesim or from Stage: its inputs (rospy glue)."""
import threading
import time
from dataclasses import dataclass

import rospy
from course_common.angles import yaw_from_quaternion
from course_common.finite import is_finite_number
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from multi_sync.laser_ahead import nearest_ahead_m
from multi_sync.motion import STAGE, TURTLESIM, distance_to_wall

# Without the inputs it needs this long, the robot subscribes to them again. The master tells
# a subscriber about a new publisher (a turtle spawned, or stageros started, after the robot)
# once, by a publisherUpdate call; rospy does not retry a lost one, so on a loaded machine a
# robot could wait forever (seen once in team20: robot 3 never connected). Subscribing again
# asks the master for the publishers it has now.
RESUBSCRIBE_S = 5.0
WARN_PERIOD_S = 5.0


@dataclass(frozen=True)
class Fix:
    """The robot's pose (world frame: x, y in m, theta in rad) and the free distance ahead
    (m; inf when the laser sees nothing in range)."""

    x: float
    y: float
    theta: float
    ahead_m: float


class RobotSensors:
    """The robot's pose and the free distance ahead, from whichever simulator runs the robot.

    The first pose to arrive names the simulator; the other inputs are unsubscribed. A robot
    told its simulator (simulator=STAGE: the Stage lesson's move_robot_sync) subscribes to
    that simulator's inputs only, and never loads turtlesim's messages.

    Subscribes (relative names: namespaces and remaps apply):
        robot_<id>/pose (turtlesim/Pose): turtlesim's pose; the free distance ahead is the
            distance to the edge of turtlesim's square world along the heading.
        robot_<id>/base_pose_ground_truth (nav_msgs/Odometry): Stage's world pose. (Its
            odom is the world pose too in Stage 4.3 with the default localization "gps", but
            drifts with "odom"; the ground truth is what the world file places.)
        robot_<id>/base_scan (sensor_msgs/LaserScan): Stage's laser; the free distance ahead
            is its nearest reading within cone_half_angle_rad of the heading. In the lesson's
            world the beams pass above the other robots: it sees walls, not teammates.
    """

    def __init__(self, robot_id, cone_half_angle_rad, world_size_m, on_ready, simulator=None):
        """on_ready() is called once, from a subscriber's thread, when fix() is first known.
        simulator: TURTLESIM or STAGE if known (then world_size_m only matters on turtlesim),
        None to take the first pose's.

        Nothing is subscribed until subscribe() (a node subscribes last)."""
        if simulator not in (None, TURTLESIM, STAGE):
            raise ValueError('simulator must be %r, %r or None, got %r'
                             % (TURTLESIM, STAGE, simulator))
        self._id = robot_id
        self._cone_rad = cone_half_angle_rad
        self._world_size_m = world_size_m
        self._on_ready = on_ready
        self._lock = threading.Lock()
        self._simulator = simulator
        self._pose = None        # (x, y, theta)
        self._scan_ahead = None  # m, from the latest scan
        self._heard = {}         # input name -> time.monotonic() of its latest message
        self._ready = False
        self._inputs = {
            'base_pose_ground_truth': (Odometry, self._on_ground_truth),
            'base_scan': (LaserScan, self._on_scan),
        }
        if simulator != STAGE:
            from turtlesim.msg import Pose  # only where turtlesim may run the robot
            self._inputs['pose'] = (Pose, self._on_turtle_pose)
        self._subs = {}
        self._subscribed_at = 0.0

    # --- what the node asks ----------------------------------------------------------------
    def fix(self):
        """The latest Fix, or None until the pose (and on Stage a scan) has arrived."""
        with self._lock:
            return self._fix_locked()

    def simulator(self):
        """TURTLESIM, STAGE, or None before the first pose."""
        with self._lock:
            return self._simulator

    def missing(self):
        """What the robot still waits for, as resolved topic names ('' once it has a fix)."""
        with self._lock:
            if self._fix_locked() is not None:
                return ''
            if self._pose is None:
                return 'no pose yet on %s' % ' or '.join(
                    self._resolved(name) for name in ('pose', 'base_pose_ground_truth')
                    if name in self._inputs)
            return 'no scan yet on %s' % self._resolved('base_scan')

    def stale(self, timeout_s):
        """What the fix rests on that has been silent for timeout_s (s, wall clock), as text
        ('' when all is fresh, or before the first fix: see missing())."""
        now = time.monotonic()
        with self._lock:
            if self._fix_locked() is None:
                return ''
            silent = [(name, now - self._heard[name]) for name in sorted(self._wanted_locked())
                      if now - self._heard[name] > timeout_s]
        return ', '.join('nothing on %s for %.1f s' % (self._resolved(name), age)
                         for name, age in silent)

    def resubscribe_if_silent(self, timeout_s):
        """Subscribe again, at most every RESUBSCRIBE_S, while an input is missing (see above)
        or has been silent for timeout_s (a publisher that dropped the connection)."""
        if time.monotonic() - self._subscribed_at < RESUBSCRIBE_S:
            return
        if self.fix() is None or (timeout_s > 0.0 and self.stale(timeout_s)):
            self.subscribe()

    def subscribe(self):
        """(Re)subscribe to every input the robot still needs."""
        with self._lock:
            wanted = self._wanted_locked()
            old, self._subs = self._subs, {}
        for sub in old.values():
            sub.unregister()
        subs = {name: rospy.Subscriber(self._topic(name), msg_type, callback, queue_size=1)
                for name, (msg_type, callback) in self._inputs.items() if name in wanted}
        with self._lock:
            self._subs.update(subs)
            self._subscribed_at = time.monotonic()
        # A first pose may have named the simulator meanwhile.
        self._drop_unwanted()

    # --- callbacks -------------------------------------------------------------------------
    def _on_turtle_pose(self, msg):
        self._take_pose(TURTLESIM, msg.x, msg.y, msg.theta)

    def _on_ground_truth(self, msg):
        p = msg.pose.pose
        q = p.orientation
        try:
            theta = yaw_from_quaternion(q.x, q.y, q.z, q.w)
        except ValueError as err:
            self._warn('ignoring a ground-truth pose: %s' % err)
            return
        self._take_pose(STAGE, p.position.x, p.position.y, theta)

    def _on_scan(self, msg):
        try:
            ahead = nearest_ahead_m(msg.ranges, msg.angle_min, msg.angle_increment,
                                    msg.range_min, msg.range_max, self._cone_rad)
        except ValueError as err:
            self._warn('ignoring a scan on %s: %s' % (self._resolved('base_scan'), err))
            return
        with self._lock:
            self._scan_ahead = ahead
            self._heard['base_scan'] = time.monotonic()
        self._maybe_ready()

    def _take_pose(self, simulator, x, y, theta):
        if not all(is_finite_number(v) for v in (x, y, theta)):
            self._warn('ignoring a %s pose that is not finite: (%r, %r, %r)'
                       % (simulator, x, y, theta))
            return
        with self._lock:
            first = self._pose is None
            if self._simulator is None:
                self._simulator = simulator
            elif self._simulator != simulator:
                return  # a pose of the other simulator's kind, arriving as it is dropped
            self._pose = (float(x), float(y), float(theta))
            self._heard['pose' if simulator == TURTLESIM else 'base_pose_ground_truth'] = \
                time.monotonic()
            if first:
                # Under the lock: the scan's thread could otherwise find the robot ready and
                # log its ready status before this line says which simulator drives it.
                rospy.loginfo('Robot %d: driven by %s', self._id, simulator)
        if first:
            self._drop_unwanted()
        self._maybe_ready()

    def _maybe_ready(self):
        with self._lock:
            first = not self._ready and self._fix_locked() is not None
            self._ready = self._ready or first
        if first:
            self._on_ready()

    # --- helpers ---------------------------------------------------------------------------
    def _drop_unwanted(self):
        """Unsubscribe the inputs of the simulator that does not run this robot."""
        with self._lock:
            wanted = self._wanted_locked()
            dropped = [self._subs.pop(n) for n in list(self._subs) if n not in wanted]
        for sub in dropped:
            sub.unregister()

    def _fix_locked(self):
        if self._pose is None:
            return None
        x, y, theta = self._pose
        if self._simulator == TURTLESIM:
            return Fix(x, y, theta, distance_to_wall(x, y, theta, self._world_size_m))
        if self._scan_ahead is None:
            return None
        return Fix(x, y, theta, self._scan_ahead)

    def _wanted_locked(self):
        if self._simulator == TURTLESIM:
            return {'pose'}
        if self._simulator == STAGE:
            return {'base_pose_ground_truth', 'base_scan'}
        return set(self._inputs)

    def _topic(self, name):
        return 'robot_%d/%s' % (self._id, name)

    def _resolved(self, name):
        return rospy.resolve_name(self._topic(name))

    def _warn(self, text):
        rospy.logwarn_throttle(WARN_PERIOD_S, 'Robot %d: %s' % (self._id, text))
