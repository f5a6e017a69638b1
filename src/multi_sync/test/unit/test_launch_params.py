"""The robots' parameters the launch files set, as roslaunch reads them (no master): none
unless an argument asks, so move_robot's defaults (DriveLimits') hold."""
import os

import pytest
import roslaunch.config
import rospkg

DRIVE_PARAMS = ('speed_mps', 'stop_distance_m', 'min_gap_m')


def robot_params(name, *args):
    """{(robot node, parameter): value} of the robots' private parameters that name sets."""
    path = os.path.join(rospkg.RosPack().get_path('multi_sync'), 'launch', name)
    config = roslaunch.config.load_config_default([(path, list(args))], None)
    found = {}
    for key, param in config.params.items():
        node, _, leaf = key.strip('/').rpartition('/')
        if node.startswith('move_robot_'):
            found[(node, leaf)] = param.value
    return found


@pytest.mark.parametrize('name, args', [
    ('multi_sync.launch', ()),                     # the lesson's file, as printed
    ('multi_sync_turtlesim.launch', ()),
    ('multi_sync_turtlesim.launch', ('team_size:=20',)),
    ('robots.launch', ('id:=2', 'team_size:=4')),
])
def test_without_arguments_the_nodes_defaults_hold(name, args):
    assert robot_params(name, *args) == {}


@pytest.mark.parametrize('name, args, robots', [
    ('multi_sync.launch', (), range(4)),
    ('multi_sync_turtlesim.launch', (), range(4)),
    ('robots.launch', ('id:=2', 'team_size:=4'), range(2, 4)),
])
def test_each_argument_given_reaches_every_robot(name, args, robots):
    given = ('speed_mps:=1.0', 'stop_distance_m:=0', 'min_gap_m:=2.5')
    assert robot_params(name, *args, *given) == {
        ('move_robot_%d' % i, param): value for i in robots
        for param, value in zip(DRIVE_PARAMS, (1.0, 0, 2.5), strict=True)}


def test_one_argument_sets_only_its_parameter():
    assert robot_params('multi_sync_turtlesim.launch', 'team_size:=2', 'min_gap_m:=0') == {
        ('move_robot_0', 'min_gap_m'): 0, ('move_robot_1', 'min_gap_m'): 0}
