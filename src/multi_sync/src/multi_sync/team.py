"""Team bookkeeping for the synchronisation lesson: who is ready, and GO (no rospy).

The argv checks of the monitor and the robots are course_common.robot_ids'.
"""
from dataclasses import dataclass, field
from enum import Enum

from course_common.robot_ids import MAX_ROBOTS, valid_robot_id

# header.frame_id of the monitor's GO message; robots treat any status with it as GO.
MONITOR_FRAME_ID = 'monitor'


class Outcome(Enum):
    """What the monitor should do about one status message."""

    NEW_READY = 'new ready'        # a robot reported ready for the first time; not all yet
    TEAM_READY = 'team ready'      # this report completed the team: log GO and publish it
    DUPLICATE = 'duplicate'        # already counted, before GO: nothing to do
    AFTER_GO = 'after go'          # a report after GO: its sender gets GO as a subscriber
    NOT_READY = 'not ready'        # is_ready false: ignored
    BAD_ID = 'bad id'              # id outside 0..MAX_ROBOTS-1: warn and ignore
    MONITOR = 'monitor'            # a monitor's own message (its GO): ignore


@dataclass
class TeamBook:
    """The monitor's record of which robots are ready, and whether GO was given.

    GO is given once, when team_size distinct valid ids have reported ready. A ready report
    after GO is recorded and asks for nothing: every subscriber gets GO exactly once, when
    it is given or as it subscribes (multi_sync.go_latch). Answering such a report with a
    second GO was the flake "2 != 1 : one GO": a robot re-announces every second until it
    reads GO, so its report can cross the GO on its way to it.
    """

    team_size: int
    ready_ids: set = field(default_factory=set)
    go_given: bool = False
    senders: dict = field(default_factory=dict)

    def __post_init__(self):
        if isinstance(self.team_size, bool) or not isinstance(self.team_size, int) \
                or not 1 <= self.team_size <= MAX_ROBOTS:
            raise ValueError('team_size must be an integer in 1..%d, got %r'
                             % (MAX_ROBOTS, self.team_size))

    @property
    def ready_count(self):
        """How many distinct robots have reported ready."""
        return len(self.ready_ids)

    def report(self, robot_id, is_ready, frame_id='', sender=''):
        """Record one RobotStatus (robot_id, is_ready, header.frame_id); return an Outcome.

        sender names the node that sent it ('' if unknown); see unconnected().
        """
        if frame_id == MONITOR_FRAME_ID:
            return Outcome.MONITOR
        if not valid_robot_id(robot_id):
            return Outcome.BAD_ID
        if not is_ready:
            return Outcome.NOT_READY
        self.senders[robot_id] = sender
        if self.go_given:
            self.ready_ids.add(robot_id)
            return Outcome.AFTER_GO
        if robot_id in self.ready_ids:
            return Outcome.DUPLICATE
        self.ready_ids.add(robot_id)
        if len(self.ready_ids) >= self.team_size:
            self.go_given = True
            return Outcome.TEAM_READY
        return Outcome.NEW_READY

    def unconnected(self, listeners):
        """Ready robots whose sender is not among listeners (the nodes GO would reach), by id.

        A robot whose sender is unknown ('') cannot be checked and counts as reachable.
        """
        return sorted(i for i in self.ready_ids
                      if self.senders.get(i, '') and self.senders[i] not in listeners)
