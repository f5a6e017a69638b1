"""The launch files that start the lesson's world, as roslaunch reads them (no master): the
lesson's stage_multi.launch, headless with gui:=false, and stage_ros's stageros.launch on the
lesson's world (its world argument is required: stage_ros depends on no lesson)."""
import os

import pytest
import roslaunch.config
import roslaunch.core
import rospkg

from stage_multi import lesson_world

HERE = os.path.dirname(os.path.abspath(__file__))
LESSON_WORLD = lesson_world.world_path()
# roslaunch's own, in every launch: those of roscore.xml (the workspace's, course_common's)
ROSLAUNCH_PARAMS = {'/rosversion', '/rosdistro', '/rosout_disable_topics_generation'}


def launch(package, name, *args):
    path = os.path.join(rospkg.RosPack().get_path(package), 'launch', name)
    return roslaunch.config.load_config_default([(path, list(args))], None)


def command_line(node):
    """The node's arguments, the world file's path made absolute and real."""
    words = node.args.split()
    return words[:-1] + [os.path.realpath(words[-1])]


@pytest.mark.parametrize('args, flags', [((), []), (('gui:=true',), []),
                                         (('gui:=false',), ['-g'])])
def test_stage_multi_launch_is_the_lessons(args, flags):
    config = launch('stage_multi', 'stage_multi.launch', *args)
    stage, *robots = config.nodes
    assert (stage.name, stage.package, stage.type) == ('stage', 'stage_ros', 'stageros')
    assert command_line(stage) == flags + [os.path.realpath(LESSON_WORLD)]
    assert [(n.name, n.package, n.type, n.args, n.output) for n in robots] == [
        ('move_robot_%d' % i, 'stage_multi', 'move_robot', str(i), 'screen') for i in range(4)]
    assert all(n.namespace == '/' for n in config.nodes)
    # no /use_sim_time nor any other parameter: the lesson's file sets none
    assert set(config.params) == ROSLAUNCH_PARAMS


@pytest.mark.parametrize('args, flags', [((), []), (('gui:=false',), ['-g'])])
def test_stageros_launch_runs_the_world_it_is_given(args, flags):
    (node,) = launch('stage_ros', 'stageros.launch', 'world:=' + LESSON_WORLD, *args).nodes
    assert command_line(node) == flags + [os.path.realpath(LESSON_WORLD)]
    assert os.path.isfile(LESSON_WORLD)


def test_stageros_launch_asks_for_its_world():
    with pytest.raises(roslaunch.core.RLException, match='world'):
        launch('stage_ros', 'stageros.launch')
