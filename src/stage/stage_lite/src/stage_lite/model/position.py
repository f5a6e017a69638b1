"""Stage 4.3's position model (libstage/model_position.cc) as its Load() reads it.

Its drive (diff, omni or car), localisation (gps or odom, with the odometry's origin and
error) and velocity bounds; its state between steps (goal, velocity, estimate) is the
World's (robot.Robot).
"""
import math

from .models import Model, read_pose
from .pose import stage_normalize
from .robot_state import PoseRow

# ModelPosition's integration error when the world gives no odom_error: each axis drawn once
# in [-E/2, E/2) (the angle's 0.05 is used as radians: it is not read from a file)
INTEGRATION_ERROR_MAX = (0.03, 0.03, 0.0, 0.05)


class Position(Model):
    """ModelPosition: drive, localisation and velocity bounds; its state lives in the World
    (its pose too: a row of the world's RobotArrays once the World has bound it)."""

    _pose_row = None

    @property
    def pose(self):
        return self._pose_row.get()

    @pose.setter
    def pose(self, value):
        if self._pose_row is None:
            self._pose_row = PoseRow(value)
        else:
            self._pose_row.set(value)

    def pose_rows(self):
        """(rows, slot): the array row the pose lives in (the world's, once bound)."""
        return self._pose_row.rows, self._pose_row.slot

    def bind_pose(self, rows, slot):
        """The pose from now on is rows[slot] (the world's RobotArrays.pose)."""
        self._pose_row.bind(rows, slot)

    def construct(self):
        self.drive = 'diff'
        self.localization = 'gps'
        self.wheelbase = 1.0
        self.velocity_bounds = [(-1.0, 1.0), (-1.0, 1.0), (-1.0, 1.0),
                                (-math.pi / 2.0, math.pi / 2.0)]
        self.initial_velocity = (0.0, 0.0, 0.0, 0.0)
        self.integration_error = None
        self.acceleration_bounds = [(-1.0, 1.0), (-1.0, 1.0), (-1.0, 1.0),
                                    (-math.pi / 2.0, math.pi / 2.0)]

    def draw_integration_error(self, rand48):
        """ModelPosition's constructor's error: four drand48() draws, the angle's first, then
        z's, y's and x's (GCC evaluates the Velocity's arguments right to left)."""
        a, z, y, x = (rand48.drand48() * m - m / 2.0 for m in INTEGRATION_ERROR_MAX[::-1])
        self.integration_error = (x, y, z, a)

    def load(self, wf, rand48):
        super().load(wf, rand48)
        e = self.entity
        v = read_pose(wf, e, 'velocity', None)
        if v is not None:
            self.initial_velocity = v
        if wf.exists(e, 'drive'):
            drive = wf.read_string(e, 'drive', 'diff')
            if drive not in ('diff', 'omni', 'car'):
                wf.warn(wf.prop(e, 'drive'), 'invalid drive "%s" (diff, omni or car); Stage'
                        ' uses "diff"' % drive)
            else:
                self.drive = drive
        self.wheelbase = wf.read_length(e, 'wheelbase', self.wheelbase)
        if wf.exists(e, 'odom'):
            wf.warn(wf.prop(e, 'odom'), 'the odom property is no longer read by Stage;'
                    ' use localization_origin')
        gpose = self.global_pose()
        self.est_origin = read_pose(wf, e, 'localization_origin', gpose)
        err = read_pose(wf, e, 'odom_error', None)
        if err is not None:          # else the constructor's draws (draw_integration_error)
            self.integration_error = err
        if wf.exists(e, 'localization'):
            loc = wf.read_string(e, 'localization', 'gps')
            if loc not in ('gps', 'odom'):
                wf.warn(wf.prop(e, 'localization'), 'unknown localization "%s" (gps or odom);'
                        ' Stage keeps "gps"' % loc)
            else:
                self.localization = loc
        ab = wf.read_tuple(e, 'acceleration_bounds', 'llllllaa')
        if ab is not None:
            self.acceleration_bounds = [(ab[0], ab[1]), (ab[2], ab[3]), (ab[4], ab[5]),
                                        (ab[6], ab[7])]
        vb = wf.read_tuple(e, 'velocity_bounds', 'llllllaa')
        if vb is not None:
            self.velocity_bounds = [(vb[0], vb[1]), (vb[2], vb[3]), (vb[4], vb[5]),
                                    (vb[6], vb[7])]

    def initial_estimate(self):
        """est_pose at load: the pose in the localisation origin's frame."""
        gx, gy, _, ga = self.global_pose()
        ox, oy, _, oa = self.est_origin
        cosa = math.cos(oa)
        sina = math.sin(oa)
        dx = gx - ox
        dy = gy - oy
        return (dx * cosa + dy * sina, dy * cosa - dx * sina, 0.0, stage_normalize(ga - oa))
