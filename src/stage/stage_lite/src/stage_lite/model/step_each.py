"""The World's step robot by robot, and Stage's position model (no rospy).

World.step runs every robot's update and move in motion.py's kernels; where those cannot
(a robot standing on another model, a model order other than the file's), the World steps
as here: the same rules, one robot at a time.
test_stage_batches.py holds the two to the same run, bit for bit.
"""

import numpy as np

from . import grid
from .blobfinder import Blobfinder
from .fiducial import Fiducial
from .motion import odometry_step
from .pose import pose_add, stage_normalize
from .robot import body_row
from .scheduler import CB_UPDATE


class RobotByRobot:
    """World's step and position model, one robot at a time (a mixin of World)."""

    def _step_each(self):
        """step() robot by robot (a robot stands on another model)."""
        self.sim_time_us += self.interval_us
        now = self.sim_time_us
        dt = self.interval_us / 1e6
        scheduler = self.scheduler
        self.fiducial_index.begin_step()
        updated = [scheduler.due(0, now)]
        for m in updated[0]:
            r = self._robot_of.get(m)
            if r is not None:
                self._update_position(r, dt, scheduler.subscribed(m))
            elif isinstance(m, Blobfinder):
                m.update(self.sight, (self.updates + 1) % 2)
        self.cameras.update(now)
        layer = self.updates % 2
        before = self.state.pose.copy() if self.race is not None else None
        for r in self._movers:                    # Stage's active_velocity, in its order
            old = r.pose
            if scheduler.subscribed(r.model):
                self._move(r, dt, layer)
            new = r.pose
            r.truth_twist = ((new[0] - old[0]) / dt, (new[1] - old[1]) / dt,
                             stage_normalize(new[2] - old[2]) / dt)
        for queue in range(1, self.threads + 1):
            updated.append(scheduler.due(queue, now))
        chosen = np.array([m in self._sensor_ids for models in updated for m in models],
                          np.bool_)
        rangers = [m for models in updated for m in models if m in self._sensor_ids]
        if rangers:
            stale = self._stale(updated, chosen)
            if stale is not None:
                stale = np.repeat(stale, [len(self._sensor_ids[g]) for g in rangers])
            self.cast_rays([k for g in rangers for k in self._sensor_ids[g]],
                           (self.updates + 1) % 2, stale, before)
        for models in updated[1:]:
            for m in models:
                if isinstance(m, Fiducial):
                    m.update(self.fiducial_index, self.sight, (self.updates + 1) % 2)
        for models in updated:
            for m in models:
                if scheduler.has_callbacks(m, CB_UPDATE):
                    scheduler.call(m, CB_UPDATE)
        scheduler.call_world(self)
        self.energy.update()                # Stage's UpdateCharge of active_energy
        if rangers:
            self._refresh_views(rangers)    # what stageros then reads, callbacks' changes in
        self.updates += 1

    # ---- Stage's position model ------------------------------------------------------------
    def _update_position(self, r, dt, subscribed=True):
        """ModelPosition::Update: the goal turned into the velocity (only while subscribed:
        a model nobody subscribes keeps its velocity), then the estimate."""
        m = r.model
        if subscribed:
            vel = r.commanded_velocity(dt)
            self.energy.position_updated(m, vel)
            for k, (lo, hi) in enumerate(m.velocity_bounds):
                vel[k] = lo if vel[k] < lo else (hi if vel[k] > hi else vel[k])
            r.velocity = tuple(vel)
        else:
            vel = [0.0, 0.0, 0.0, 0.0]
        if m.localization == 'gps':
            r.est_pose = m.global_pose()
        else:
            ex, ey, _, ea = m.integration_error
            x, y, z, a = r.est_pose
            x, y, a = odometry_step(x, y, a, vel[0], vel[1], vel[3], dt, ex, ey, ea)
            r.est_pose = (x, y, z, a)

    def _move(self, r, dt, layer):
        """ModelPosition::Move: the provisional move, drawn in `layer`, undone on a
        collision."""
        vx, vy, vz, va = r.velocity
        if not (vx or vy or vz or va):
            return
        m = r.model
        start = m.pose
        old = self._body_rows(r)
        m.pose = pose_add(start, (vx * dt, vy * dt, vz * dt, stage_normalize(va * dt)))
        if not len(r.block_ids):
            r.stalled = False
            return
        new = self._body_rows(r)
        seqs = np.array([self._seqs(r), self._seqs(r)])
        if self.space.move(r.block_ids, new, old, seqs, layer) != grid.NO_HIT:
            m.pose = start
            r.stalled = True
        else:
            r.stalled = False

    @staticmethod
    def _body_rows(r):
        """Per block of the robot's tree: its model's body pose (x, y, cos, sin)."""
        return np.array([row for m, ks in r.blocks for row in [body_row(m)] * len(ks)])

    def _seqs(self, r):
        """Per block of the robot's tree: a new drawing number per model (MapWithChildren)."""
        return np.array([s for m, ks in r.blocks for s in [self.space.next_seq()] * len(ks)],
                        np.int64)

