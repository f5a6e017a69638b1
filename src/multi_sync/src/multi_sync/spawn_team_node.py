"""Spawns robots robot_<first_id>..robot_<team_size-1> in turtle_lite at the team layout."""
import sys
from dataclasses import dataclass

import rospy
from course_common.param_loader import load_or_exit
from course_common.params import check_int, check_number
from course_common.robot_ids import MAX_ROBOTS
from course_common.startup import init_node
from turtlesim.srv import Spawn

from multi_sync.motion import team_layout


@dataclass(frozen=True)
class SpawnTeamConfig:
    """spawn_team's private parameters (see SpawnTeam)."""

    team_size: int = 4
    first_id: int = 1
    wait_s: float = 60.0


def load_config(get_param=rospy.get_param):
    """Read and check the private parameters; raise ValueError naming the bad one."""
    size = get_param('~team_size', SpawnTeamConfig.team_size)
    first = get_param('~first_id', SpawnTeamConfig.first_id)
    wait = get_param('~wait_s', SpawnTeamConfig.wait_s)
    size = check_int('~team_size', size, 1, MAX_ROBOTS)
    first = check_int('~first_id', first, 0, size)
    wait = check_number('~wait_s', wait, 0.0, 3600.0, low_open=True, high_open=True)
    return SpawnTeamConfig(size, first, wait)


class SpawnTeam:
    """Calls the simulator's spawn service once per robot, then the node exits.

    A robot whose name already exists is reported and skipped, so relaunching against a
    running simulator works.

    Subscribes: none.  Publishes: none.
    Services called:
        spawn (turtlesim/Spawn): one call per robot, name robot_<id>, pose from
            multi_sync.motion.team_layout (heading +x).
    Parameters (private):
        ~team_size (int, 4): robots in the team; robots first_id..team_size-1 are spawned.
        ~first_id (int, 1): first id to spawn (robot_0 is the simulator's turtle1, remapped).
        ~wait_s (float, 60 s): how long to wait for the spawn service.
    """

    def __init__(self, config):
        self._cfg = config
        self._spawn = rospy.ServiceProxy('spawn', Spawn)

    def run(self):
        """Spawn the robots; return False when the spawn service never appeared."""
        try:
            self._spawn.wait_for_service(self._cfg.wait_s)
        except rospy.ROSException:
            rospy.logerr('spawn_team: service %s did not appear within %.0f s'
                         % (rospy.resolve_name('spawn'), self._cfg.wait_s))
            return False
        layout = team_layout(self._cfg.team_size)
        for robot_id in range(self._cfg.first_id, self._cfg.team_size):
            x, y, theta = layout[robot_id]
            name = 'robot_%d' % robot_id
            try:
                self._spawn(x, y, theta, name)
                rospy.loginfo('spawn_team: %s at x=%.3f y=%.3f', name, x, y)
            except rospy.ServiceException as err:
                # turtlesim refuses an existing name with an empty error text.
                rospy.logwarn('spawn_team: could not spawn %s (already there?): %s'
                              % (name, err))
        return True


def main():
    """rosrun multi_sync spawn_team _team_size:=N [_first_id:=1]."""
    init_node('spawn_team')
    config = load_or_exit(load_config, 'spawn_team')
    if not SpawnTeam(config).run():
        sys.exit(1)
