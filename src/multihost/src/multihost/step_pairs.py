"""Pairing the two halves of a Stage step (pure: no rospy).

stageros publishes a robot's ground truth and its odom once per step, each stamped with the
step's sim time, on two topics: a subscriber receives them in either order. The team probe
wants both at once (where the robot is, and the speed Stage applies to it), so it pairs them
by stamp.
"""

# Steps kept waiting for their other half: a second of Stage's 10 Hz steps. The bound when one
# of a robot's two topics is silent (its publisher gone, or not connected yet).
UNPAIRED_STEPS = 10


class StepPairs:
    """Halves of steps by robot and stamp; a step is whole once it has every field of fields."""

    def __init__(self, fields, unpaired_steps=UNPAIRED_STEPS):
        if unpaired_steps < 1:
            raise ValueError('unpaired_steps = %r: expected at least 1' % (unpaired_steps,))
        self._fields = frozenset(fields)
        self._limit = unpaired_steps
        self._halves = {}  # robot: {stamp_ns: {field: value}}

    def add(self, robot, stamp_ns, **half):
        """Add half of robot's step stamp_ns; return the whole step's fields once complete.

        A whole step drops that robot's older halves (their other half will not come: Stage
        publishes in step order); beyond unpaired_steps waiting steps the oldest goes.
        """
        unknown = set(half) - self._fields
        if unknown:
            raise ValueError('fields %s: expected some of %s' % (sorted(unknown),
                                                                 sorted(self._fields)))
        halves = self._halves.setdefault(robot, {})
        step = halves.setdefault(stamp_ns, {})
        step.update(half)
        whole = dict(step) if set(step) == self._fields else None
        for old in sorted(halves):
            if (whole is not None and old <= stamp_ns) or len(halves) > self._limit:
                del halves[old]
        return whole

    def waiting(self, robot):
        """The stamps of robot's steps still waiting for a half, oldest first."""
        return sorted(self._halves.get(robot, {}))
