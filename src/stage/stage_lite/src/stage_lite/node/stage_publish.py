"""stageros's per-step output: odom, ground truth, scans, one /tf message and /clock.

Each step's messages are packed as TCPROS frames (stage_lite.wire) from the world's numbers
and arrays, only for topics that have subscribers, and written by
course_common.rospy_internals.write_frames (no message objects, no rospy send queues).
collect() runs under the node's lock (it reads the world); send() runs outside it.
"""
import time

import rosgraph
import rospy
from course_common.publishers import unqueued_publisher
from course_common.rospy_internals import deliver_bodies, has_subscribers, write_frames
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Bool
from tf2_msgs.msg import TFMessage

from . import wire
from .robot_frames import RobotFrames

#: stageros's queue sizes (advertise<...>(name, 10), subscribe(cmd_vel, 10)).
QUEUE_SIZE = 10


class RobotOutput:
    """One robot's publishers and its cmd_vel subscriber."""

    def __init__(self, index, names, params, on_cmd_vel, on_cmd_vel_bodies):
        self.index = index
        self.names = names
        self.odom_pub = unqueued_publisher(names.odom, Odometry)
        self.truth_pub = unqueued_publisher(names.ground_truth, Odometry)
        self.scan_pubs = [unqueued_publisher(topic, LaserScan) for topic in names.scans]
        self.stall_pub = (rospy.Publisher(names.stall, Bool, queue_size=1, latch=True)
                          if params.publish_stall else None)
        self.last_stall = None
        # Subscribed last: the callback may run at once.
        self.cmd_sub = rospy.Subscriber(names.cmd_vel, Twist, on_cmd_vel, callback_args=index,
                                        queue_size=QUEUE_SIZE)
        deliver_bodies(self.cmd_sub, lambda bodies, _conn: on_cmd_vel_bodies(bodies, index))

    def stall_changed(self, robot):
        """The stall value to publish if it changed (None otherwise or when switched off)."""
        if self.stall_pub is None or robot.stalled == self.last_stall:
            return None
        self.last_stall = bool(robot.stalled)
        return self.last_stall


class StepOutput:
    """Every robot's output plus the global /clock and /tf."""

    def __init__(self, world, names, params, on_cmd_vel, on_cmd_vel_bodies, cameras=None):
        """on_cmd_vel(msg, index) and on_cmd_vel_bodies(bodies, index): a robot's cmd_vel
        as messages or as their bodies (rospy_internals.deliver_bodies)."""
        self.cameras = cameras      # camera_publish.CameraOutputs, or None
        self.clock_pub = unqueued_publisher('/clock', Clock)
        self.tf_pub = unqueued_publisher('/tf', TFMessage)
        self.packed = RobotFrames(world, names, params.odom_child_frame)
        self.robots = [RobotOutput(i, n, params, on_cmd_vel, on_cmd_vel_bodies)
                       for i, n in enumerate(names)]
        # (publisher, its frame, the RangerView whose data it waits for, or None) in the
        # order stageros publishes: each robot's odom, ground truth, then its scans
        self._robot_frames = []
        for i, output in enumerate(self.robots):
            self._robot_frames += [(output.odom_pub, self.packed.odom[i], None),
                                   (output.truth_pub, self.packed.truth[i], None)]
            self._robot_frames += list(zip(output.scan_pubs, self.packed.scans[i],
                                           self.packed.views[i], strict=True))
        self.publish_stall = params.publish_stall
        # The headers' seq: the steps published before this one (roscpp counts a
        # publisher's messages whether anybody listens or not, so stageros's seq is that).
        self.steps_published = 0
        # Each kind's publishers: a kind nobody subscribes to is not packed, and a step with
        # no robot topic subscribed (the flat-out benchmark) skips the loop over the robots.
        self._odom_pubs = [output.odom_pub for output in self.robots]
        self._truth_pubs = [output.truth_pub for output in self.robots]
        self._scan_pubs = [pub for output in self.robots for pub in output.scan_pubs]
        self._robot_pubs = self._odom_pubs + self._truth_pubs + self._scan_pubs

    def wait_for_waiting_subscribers(self, timeout_s, poll_s=0.002):
        """Wait (at most timeout_s) until the subscribers that the master already lists for
        our topics have connected, so that the first step reaches them. True if they all did.

        A subscriber connects only after the master has told it about the new publisher:
        without this wait, a node that was there first sees the second step first.
        """
        me = rospy.get_name()
        try:
            _, subscribed, _ = rosgraph.Master(me).getSystemState()
        except (OSError, rosgraph.MasterError):
            return False
        waiting = {topic: sum(1 for node in nodes if node != me) for topic, nodes in subscribed}
        wanted = [(pub, waiting.get(pub.resolved_name, 0))
                  for pub in (self.clock_pub, self.tf_pub, *self._robot_pubs,
                              *(self.cameras.publishers if self.cameras else ()))]
        deadline = time.monotonic() + timeout_s
        while any(pub.get_num_connections() < count for pub, count in wanted):
            if time.monotonic() >= deadline:
                return False
            time.sleep(poll_s)
        return True

    def collect(self, world, stamp):
        """(frames, stalls) of this step: [(publisher, frame)], [(publisher, Bool value)]."""
        secs, nsecs = stamp
        seq = self.steps_published
        self.steps_published += 1
        frames = []
        stalls = []
        packed = self.packed
        kinds = [any(map(has_subscribers, pubs))
                 for pubs in (self._odom_pubs, self._truth_pubs, self._scan_pubs)]
        with_tf = has_subscribers(self.tf_pub)
        packed.fill(seq, secs, nsecs, *kinds, tf=with_tf)
        if any(kinds):
            for pub, frame, view in self._robot_frames:
                # stageros publishes a ranger once it has ranges: after its first update
                if pub.impl.connections and (view is None or view.has_data):
                    frames.append((pub, frame))
        camera_tf = self.cameras.collect(world, secs, nsecs, frames) if self.cameras else []
        if self.publish_stall:
            for output, robot in zip(self.robots, world.robots, strict=True):
                stall = output.stall_changed(robot)
                if stall is not None:
                    stalls.append((output.stall_pub, stall))
        if with_tf:
            # One message for every robot's transforms (stageros sends one per transform).
            tf = packed.tf
            if camera_tf:
                # the robots' transforms (after the frame's length and count), the cameras'
                tf = wire.tf_frame([bytes(tf[8:]), *camera_tf],
                                   count=packed.tf_count + len(camera_tf))
            frames.append((self.tf_pub, tf))
        if has_subscribers(self.clock_pub):
            frames.append((self.clock_pub, wire.clock_frame(secs, nsecs)))
        return frames, stalls

    @staticmethod
    def send(frames, stalls):
        write_frames(frames)
        for pub, value in stalls:
            pub.publish(Bool(value))
