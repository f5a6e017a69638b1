"""A robot of the world as Stage 4.3 keeps it and stageros reads it (no rospy).

Robot: a position model and the state Stage's ModelPosition keeps between steps (the goal,
i.e. the last cmd_vel, the velocity, the odometry estimate, the stall), with the blocks of
its tree the grid draws as it moves; RangerView: what stageros publishes of one of its
rangers (the first sensor's scan, the tf pose). world_load makes them; the World steps them.
"""
import math

import numpy as np

from .pose import stage_normalize as _normalize
from .robot_state import MODE_CODE, MODES, RobotArrays


class RangerView:
    """What stageros publishes of a ranger: its first sensor's scan and the tf pose."""

    def __init__(self, model, sensor, robot_height):
        self.model = model
        self.sensor = sensor
        x, y, z, a = model.pose
        self.pose = (x, y, robot_height + z, a)       # base_link -> base_laser_link
        self.range_min, self.range_max = sensor.range
        self.samples = sensor.samples
        self.fov_rad = sensor.fov
        self.noise = sensor.noise
        self.ranges = np.full(self.samples, self.range_max, np.float32)
        self.intensities = np.zeros(self.samples, np.float32)
        self.has_data = False       # stageros publishes a ranger after its first update
        self.beam_z = model.ray_origin(sensor)[2]

    @property
    def angle_min(self):
        return -self.fov_rad / 2.0

    @property
    def angle_increment(self):
        # stageros divides by samples - 1 even when it is 0 (IEEE: inf, or nan for fov 0)
        if self.samples > 1:
            return self.fov_rad / (self.samples - 1)
        return math.inf if self.fov_rad > 0 else math.nan

    def local_angles(self):
        """The beams' angles in the sensor's frame (a one-beam sensor's: angle_min)."""
        step = self.fov_rad / (self.samples - 1) if self.samples > 1 else 0.0
        return self.angle_min + np.arange(self.samples) * step


class Robot:
    """A position model and its Stage state (goal, velocity, estimate, stall): rows of a
    RobotArrays (robot_state.py), its own until the World binds it to its world's."""

    def __init__(self, index, model, rangers):
        self.index = index
        self._st = RobotArrays(1)
        self._i = 0
        self.model = model
        self.model_name = model.name
        self.color_rgb = model.color[:3]
        self.size = model.geom_size
        self.origin = model.geom_pose
        self.rangers = rangers         # what stageros publishes: each ranger's first sensor
        self.ranger_models = []        # the rangers it carries that have sensors (all cast)
        self.drive = model.drive
        gp = model.global_pose()
        self.initial_global = gp
        self.start_pose = (gp[0], gp[1], gp[3])
        self.goal = (0.0, 0.0, 0.0, 0.0)
        self.control_mode = 'velocity'     # Stage's CONTROL_VELOCITY, _ACCELERATION, _POSITION
        self.velocity = model.initial_velocity
        self.est_pose = model.initial_estimate()
        self.stalled = False
        self.truth_twist = (0.0, 0.0, 0.0)
        # [(model, its block indices in the grid)] over the robot's tree (itself first) in
        # drawing order, and those indices in one array (world_load fills both)
        self.blocks = []
        self.block_ids = np.zeros(0, np.int64)

    def bind(self, state):
        """From now on the state is row `index` of `state` (the world's RobotArrays), and
        so is the position model's pose."""
        state.copy_row(self.index, self._st, self._i)
        self._st = state
        self._i = self.index
        self.model.bind_pose(state.pose, self.index)

    def command_rows(self):
        """(goal array, mode array, row) of the arrays the command lives in."""
        return self._st.goal, self._st.mode, self._i

    @property
    def goal(self):
        """The last command (x, y, z, a): cmd_vel, SetSpeed, SetAcceleration or GoTo."""
        return tuple(self._st.goal[self._i].tolist())

    @goal.setter
    def goal(self, value):
        self._st.goal[self._i] = value

    @property
    def control_mode(self):
        """'velocity', 'acceleration' or 'position' (Stage's CONTROL_*)."""
        return MODES[self._st.mode[self._i]]

    @control_mode.setter
    def control_mode(self, value):
        self._st.mode[self._i] = MODE_CODE[value]

    @property
    def velocity(self):
        return tuple(self._st.velocity[self._i].tolist())

    @velocity.setter
    def velocity(self, value):
        self._st.velocity[self._i] = value

    @property
    def est_pose(self):
        return tuple(self._st.est[self._i].tolist())

    @est_pose.setter
    def est_pose(self, value):
        self._st.est[self._i] = value

    @property
    def stalled(self):
        return bool(self._st.stalled[self._i])

    @stalled.setter
    def stalled(self, value):
        self._st.stalled[self._i] = value

    @property
    def truth_twist(self):
        """Ground truth's twist over the last step (vx, vy, wz)."""
        return tuple(self._st.twist[self._i].tolist())

    @truth_twist.setter
    def truth_twist(self, value):
        self._st.twist[self._i] = value

    def commanded_velocity(self, dt):
        """ModelPosition::Update's velocity from the goal, before velocity_bounds: [x, y, z,
        a]. Velocity control (cmd_vel, SetSpeed) by drive; acceleration control
        (SetAcceleration) adds the bounded goal * dt to the velocity; position control
        (GoTo) steers toward the goal pose from the estimate, as Stage's simple law does."""
        m = self.model
        gx, gy, gz, ga = self.goal
        if self.control_mode == 'acceleration':
            (ax0, ax1), (ay0, ay1), _, (aa0, aa1) = m.acceleration_bounds
            gx = min(max(gx, ax0), ax1)
            gy = min(max(gy, ay0), ay1)
            ga = min(max(ga, aa0), aa1)
            vx, vy, vz, va = self.velocity
            if m.drive == 'omni':
                return [vx + gx * dt, vy + gy * dt, vz, va + ga * dt]
            if m.drive == 'car':
                return [vx, vy, vz, va]   # Stage: "car drive not supported in acceleration"
            return [vx + gx * dt, 0.0, vz, va + ga * dt]
        if self.control_mode == 'position':
            return self._toward_goal()
        if m.drive == 'omni':
            return [gx, gy, 0.0, ga]
        if m.drive == 'car':
            return [gx * math.cos(ga), 0.0, 0.0, gx * math.sin(ga) / m.wheelbase]
        return [gx, 0.0, 0.0, ga]

    def _toward_goal(self):
        """CONTROL_POSITION: speed limits 0.4 m/s and 1 rad/s, hard-coded in Stage; its
        turn is max(error, -1) (Stage's min is overwritten: kept)."""
        gx, gy, _, ga = self.goal
        ex, ey, _, ea = self.est_pose
        x_err, y_err = gx - ex, gy - ey
        a_err = _normalize(ga - ea)
        if self.model.drive == 'omni':
            return [min(x_err, 0.4), min(y_err, 0.4), 0.0, min(a_err, 1.0)]
        vx = 0.0
        if abs(x_err) < 0.02 and abs(y_err) < 0.02:
            va = max(a_err, -1.0)
        else:
            a_err = _normalize(math.atan2(y_err, x_err) - ea)
            va = max(a_err, -1.0)
            if abs(a_err) < math.pi / 16:
                # the C library's hypot, as Stage's (math.hypot differs in the last bit at
                # times: then the robot's speed, and its path, would not be Stage's)
                vx = min(float(np.hypot(y_err, x_err)), 0.4)
        return [vx, 0.0, 0.0, va]

    @property
    def pose(self):
        """(x, y, yaw): the world pose (ground truth)."""
        x, y, _, a = self.model.global_pose()
        return (x, y, a)

    @property
    def odom_pose(self):
        x, y, _, a = self.est_pose
        return (x, y, a)

    @property
    def command(self):
        """The velocity Stage applies (odom's twist): vx, vy, wz."""
        return (self.velocity[0], self.velocity[1], self.velocity[3])


def body_row(m):
    """The model's body pose as the grid kernels take it: (x, y, cos a, sin a)."""
    x, y, _, a = m.body_pose()
    return (x, y, math.cos(a), math.sin(a))
