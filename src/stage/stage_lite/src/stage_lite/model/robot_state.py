"""The robots' state between steps as arrays, one row per robot (no rospy).

A Robot's goal, control mode, velocity, estimate, stall and ground-truth twist, and its
position model's pose, are rows of these arrays (robot.Robot and position.Position read and
write them through properties), so that the step's kernels (motion.py) update every robot
at once, in place, with nothing copied back and forth. Until the World binds a robot to
its world's arrays it keeps a one-row set of its own.
"""
import numpy as np

#: Stage's CONTROL_VELOCITY, CONTROL_ACCELERATION, CONTROL_POSITION, by their row code
MODES = ('velocity', 'acceleration', 'position')
MODE_CODE = {name: code for code, name in enumerate(MODES)}


class RobotArrays:
    """The state of n robots: pose (the position model's, in its parent's frame), goal,
    mode (MODES' codes), velocity, est (the estimate), stalled, twist (ground truth's)."""

    #: the Robot's own fields (the pose is its position model's: PoseRow)
    FIELDS = ('goal', 'mode', 'velocity', 'est', 'stalled', 'twist')

    def __init__(self, n):
        self.pose = np.zeros((n, 4), np.float64)
        self.goal = np.zeros((n, 4), np.float64)
        self.mode = np.zeros(n, np.int64)
        self.velocity = np.zeros((n, 4), np.float64)
        self.est = np.zeros((n, 4), np.float64)
        self.stalled = np.zeros(n, np.bool_)
        self.twist = np.zeros((n, 3), np.float64)

    def copy_row(self, i, other, j):
        """Row i := other's row j, every field of FIELDS."""
        for name in self.FIELDS:
            getattr(self, name)[i] = getattr(other, name)[j]


class PoseRow:
    """A position model's pose as a row of RobotArrays.pose (its own until bound)."""

    __slots__ = ('rows', 'slot')

    def __init__(self, pose):
        self.rows = np.array([pose], np.float64)
        self.slot = 0

    def get(self):
        return tuple(self.rows[self.slot].tolist())

    def set(self, pose):
        self.rows[self.slot] = pose

    def bind(self, rows, slot):
        rows[slot] = self.rows[self.slot]
        self.rows = rows
        self.slot = slot
