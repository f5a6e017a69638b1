"""stageros's per-step output: odom, ground truth, scans, one /tf message and /clock.

Each step's messages are packed as TCPROS frames (stage_lite.wire) from the world's numbers
and arrays, only for topics that have subscribers, and written by
course_common.rospy_internals.write_frame (no message objects, no rospy send queues).
collect() runs under the node's lock (it reads the world); send() runs outside it.
"""
import time

import rosgraph
import rospy
from course_common.publishers import unqueued_publisher
from course_common.rospy_internals import has_subscribers, write_frame
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Bool
from tf2_msgs.msg import TFMessage

from . import wire

#: stageros's queue sizes (advertise<...>(name, 10), subscribe(cmd_vel, 10)).
QUEUE_SIZE = 10


class RobotOutput:
    """One robot's publishers, its cmd_vel subscriber and its packed frame ids."""

    def __init__(self, index, names, robot, params, on_cmd_vel):
        self.index = index
        self.names = names
        self.odom_pub = unqueued_publisher(names.odom, Odometry)
        self.truth_pub = unqueued_publisher(names.ground_truth, Odometry)
        self.scan_pubs = [unqueued_publisher(topic, LaserScan) for topic in names.scans]
        self.stall_pub = (rospy.Publisher(names.stall, Bool, queue_size=1, latch=True)
                          if params.publish_stall else None)
        self.last_stall = None
        s = wire.string_bytes
        self.odom_frame = s(names.odom_frame)
        self.footprint_frame = s(names.footprint_frame)
        self.base_frame = s(names.base_frame)
        self.laser_frames = [s(f) for f in names.laser_frames]
        # stageros leaves child_frame_id empty; ~odom_child_frame fills it (stage_ros PR #52).
        self.child_frame = s(names.footprint_frame if params.odom_child_frame else '')
        self.empty = s('')
        self.templates = [wire.ScanTemplate(frame, r.angle_min, r.angle_increment, r.samples,
                                            r.range_min, r.range_max)
                          for frame, r in zip(names.laser_frames, robot.rangers, strict=True)]
        # Subscribed last: the callback may run at once.
        self.cmd_sub = rospy.Subscriber(names.cmd_vel, Twist, on_cmd_vel, callback_args=index,
                                        queue_size=QUEUE_SIZE)

    def collect(self, robot, seq, secs, nsecs, out):
        """Append (publisher, frame) for every subscribed topic of this robot to out.

        seq: the header's seq, the number of steps published before this one (roscpp counts
        a publisher's messages whether anybody listens or not, so stageros's seq is that).
        """
        if has_subscribers(self.odom_pub):
            out.append((self.odom_pub, wire.odometry_frame(
                seq, secs, nsecs, self.odom_frame, self.child_frame,
                robot.odom_pose, robot.command)))
        if has_subscribers(self.truth_pub):
            out.append((self.truth_pub, wire.odometry_frame(
                seq, secs, nsecs, self.odom_frame, self.empty,
                robot.pose, robot.truth_twist, wire.transform_quaternion)))
        for pub, template, ranger in zip(self.scan_pubs, self.templates, robot.rangers,
                                         strict=True):
            # stageros publishes a ranger once it has ranges: after its first update
            if ranger.has_data and has_subscribers(pub):
                out.append((pub, template.frame(seq, secs, nsecs, ranger.ranges,
                                                ranger.intensities)))

    def transforms(self, robot, secs, nsecs):
        """odom -> base_footprint (odometry pose), -> base_link (identity), -> each laser."""
        x, y, yaw = robot.odom_pose
        packed = [wire.transform_bytes(secs, nsecs, self.odom_frame, self.footprint_frame,
                                       x, y, 0.0, yaw),
                  wire.transform_bytes(secs, nsecs, self.footprint_frame, self.base_frame,
                                       0.0, 0.0, 0.0, 0.0)]
        for frame, ranger in zip(self.laser_frames, robot.rangers, strict=True):
            lx, ly, lz, lyaw = ranger.pose
            packed.append(wire.transform_bytes(secs, nsecs, self.base_frame, frame,
                                               lx, ly, lz, lyaw))
        return packed

    def stall_changed(self, robot):
        """The stall value to publish if it changed (None otherwise or when switched off)."""
        if self.stall_pub is None or robot.stalled == self.last_stall:
            return None
        self.last_stall = bool(robot.stalled)
        return self.last_stall


class StepOutput:
    """Every robot's output plus the global /clock and /tf."""

    def __init__(self, world, names, params, on_cmd_vel, cameras=None):
        self.cameras = cameras      # camera_publish.CameraOutputs, or None
        self.clock_pub = unqueued_publisher('/clock', Clock)
        self.tf_pub = unqueued_publisher('/tf', TFMessage)
        self.robots = [RobotOutput(i, n, r, params, on_cmd_vel)
                       for i, (n, r) in enumerate(zip(names, world.robots, strict=True))]
        self.publish_stall = params.publish_stall
        self.steps_published = 0  # the headers' seq (see RobotOutput.collect)
        # Every robot's per-step publishers: one any() over them per step lets a step with
        # no robot topic subscribed (the flat-out benchmark) skip the loop over the robots.
        self._robot_pubs = [pub for output in self.robots
                            for pub in (output.odom_pub, output.truth_pub, *output.scan_pubs)]

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
        if any(map(has_subscribers, self._robot_pubs)):
            for output, robot in zip(self.robots, world.robots, strict=True):
                output.collect(robot, seq, secs, nsecs, frames)
        camera_tf = self.cameras.collect(world, secs, nsecs, frames) if self.cameras else []
        if self.publish_stall:
            for output, robot in zip(self.robots, world.robots, strict=True):
                stall = output.stall_changed(robot)
                if stall is not None:
                    stalls.append((output.stall_pub, stall))
        if has_subscribers(self.tf_pub):
            # One message for every robot's transforms (stageros sends one per transform).
            packed = []
            for output, robot in zip(self.robots, world.robots, strict=True):
                packed.extend(output.transforms(robot, secs, nsecs))
            packed.extend(camera_tf)
            frames.append((self.tf_pub, wire.tf_frame(packed)))
        if has_subscribers(self.clock_pub):
            frames.append((self.clock_pub, wire.clock_frame(secs, nsecs)))
        return frames, stalls

    @staticmethod
    def send(frames, stalls):
        for pub, frame in frames:
            write_frame(pub, frame)
        for pub, value in stalls:
            pub.publish(Bool(value))
