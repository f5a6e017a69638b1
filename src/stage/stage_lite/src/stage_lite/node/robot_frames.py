"""Every robot's frames of a step, packed at once: odometry, ground truth, scans and the one
/tf message (no rospy).

stageros on a swarm sends a few messages per robot every step; packed one message at a time
they were most of its step at 100 robots. RobotFrames keeps each kind in a wire.FrameBatch
and writes the step's numbers for every robot from the world's arrays in a few array
operations, the bytes equal to rospy's serialisation of the same messages (test_robot_frames).
"""
import numpy as np

from . import wire

#: the columns of robot_state's estimate and velocity that stageros publishes: x, y, yaw
XY_YAW = [0, 1, 3]


class RobotFrames:
    """The frames of `world`'s robots, named by names.all_robot_names' RobotNames.

    After fill(): odom[i], truth[i] (wire.FrameBatch frames), scans[i] (robot i's scans, one
    per RangerView, with views[i] beside them) and tf (every robot's transforms, one
    message: odom -> base_footprint, -> base_link, -> each laser; tf_count of them).
    odom_child_frame: odometry's child_frame_id is base_footprint (~odom_child_frame), else
    empty as in stageros.
    """

    def __init__(self, world, names, odom_child_frame):
        s = wire.string_bytes
        self.world = world
        robots = world.robots
        self._odom = wire.FrameBatch([
            wire.odometry_parts(s(n.odom_frame), s(n.footprint_frame if odom_child_frame
                                                   else '')) for n in names])
        self._truth = wire.FrameBatch([wire.odometry_parts(s(n.odom_frame), s(''))
                                       for n in names])
        self.views = [list(r.rangers) for r in robots]
        self._all_views = [v for views in self.views for v in views]
        scan_parts = [wire.scan_parts(wire.ScanTemplate(frame, v.angle_min, v.angle_increment,
                                                        v.samples, v.range_min, v.range_max))
                      for n, views in zip(names, self.views, strict=True)
                      for frame, v in zip(n.laser_frames, views, strict=True)]
        self._scans = wire.FrameBatch(scan_parts) if scan_parts else None
        tf_parts = []
        for n, views in zip(names, self.views, strict=True):
            tf_parts += wire.transform_parts(s(n.odom_frame), s(n.footprint_frame))
            tf_parts += wire.transform_parts(s(n.footprint_frame), s(n.base_frame),
                                             (0.0, 0.0, 0.0, 0.0))
            for frame, v in zip(n.laser_frames, views, strict=True):
                tf_parts += wire.transform_parts(s(n.base_frame), s(frame), v.pose)
        self.tf_count = sum(2 + len(views) for views in self.views)
        self._tf = wire.FrameBatch([[wire.uint32_bytes(self.tf_count), *tf_parts]])
        self.odom = self._odom.frames
        self.truth = self._truth.frames
        self.tf = self._tf.frames[0]
        frames = self._scans.frames if self._scans else []
        self.scans = []
        for views in self.views:
            self.scans.append(frames[:len(views)])
            frames = frames[len(views):]

    def fill(self, seq, secs, nsecs, odom=True, truth=True, scans=True, tf=True):
        """Writes this step's numbers into the frames asked for (seq: the headers' seq)."""
        if not self.views:
            return      # no robot: nothing changes (/tf is an empty message)
        state = self.world.state
        stamp = wire.HEADER_STAMP.pack(seq, secs, nsecs)
        if odom or tf:
            odom_pose = state.est[:, XY_YAW]
            odom_quaternions = wire.yaw_quaternions(odom_pose[:, 2])
        if odom:
            velocity = state.velocity[:, XY_YAW]
            poses, twists = wire.odometry_rows(odom_pose, velocity, odom_quaternions)
            self._odom.fill('stamp', stamp)
            self._odom.write('pose', poses)
            self._odom.write('twist', twists)
        if truth:
            true_pose = self.world.robot_poses()
            poses, twists = wire.odometry_rows(true_pose, state.twist,
                                               wire.transform_quaternions(true_pose[:, 2]))
            self._truth.fill('stamp', stamp)
            self._truth.write('pose', poses)
            self._truth.write('twist', twists)
        if scans and self._scans is not None:
            self._scans.fill('stamp', stamp)
            self._scans.write('ranges', _floats(v.ranges for v in self._all_views))
            self._scans.write('intensities', _floats(v.intensities for v in self._all_views))
        if tf:
            # stageros's tf::Transform: the odometry's rotation, through the matrix and back
            moving = wire.pose_rows(odom_pose, wire.matrix_round_trips(odom_quaternions))
            self._tf.fill('stamp', wire.HEADER_STAMP.pack(0, secs, nsecs))
            self._tf.write('moving', moving)


def _floats(arrays):
    arrays = list(arrays)
    return np.concatenate(arrays).astype('<f4', copy=False) if arrays else np.zeros(0, '<f4')
