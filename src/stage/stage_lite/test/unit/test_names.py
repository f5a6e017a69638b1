"""stageros's names: relative with one robot, /robot_<N>/ with several or -u, base_scan_<k>."""
import pytest
from stage_lite.node.names import all_robot_names, prefix, robot_names, shared_namespaces


@pytest.mark.parametrize('index, model, count, umn, expected', [
    (0, 'robot0', 1, False, ''),
    (0, 'robot0', 4, False, '/robot_0/'),
    (3, 'robot3', 4, False, '/robot_3/'),
    (0, 'robot0', 1, True, '/robot0/'),
    (2, 'robot2', 4, True, '/robot2/'),
    (1, '', 4, True, '/robot_1/'),
    (1, 'position:1', 2, True, '/robot_1/'),
])
def test_prefix(index, model, count, umn, expected):
    assert prefix(index, model, count, umn) == expected


def test_one_robot_is_relative_with_stage_frames():
    n = robot_names(0, 'r', 1, 1)
    assert (n.cmd_vel, n.odom, n.ground_truth, n.scans, n.stall) == \
        ('cmd_vel', 'odom', 'base_pose_ground_truth', ('base_scan',), 'stall')
    assert (n.odom_frame, n.footprint_frame, n.base_frame, n.laser_frames) == \
        ('odom', 'base_footprint', 'base_link', ('base_laser_link',))


def test_several_robots_keep_the_leading_slash_unless_tf2_frames():
    n = robot_names(2, 'r', 4, 1)
    assert n.odom == '/robot_2/odom'
    assert n.odom_frame == '/robot_2/odom'
    assert n.laser_frames == ('/robot_2/base_laser_link',)
    clean = robot_names(2, 'r', 4, 1, tf2_frames=True)
    assert clean.odom == '/robot_2/odom'  # topics stay absolute
    assert (clean.odom_frame, clean.footprint_frame, clean.base_frame, clean.laser_frames) == \
        ('robot_2/odom', 'robot_2/base_footprint', 'robot_2/base_link',
         ('robot_2/base_laser_link',))


# Every case of stage_ros 1.8.0's mapName: (index, model name, robots, rangers, -u) ->
# (odom topic, scan topics, laser frames). Per-device names (several rangers) are absolute
# even for one robot without -u.
NAME_CASES = [
    # one robot, no -u: relative; one ranger, no ranger, two rangers (absolute, no robot ns)
    (0, 'robot0', 1, 1, False, 'odom', ('base_scan',), ('base_laser_link',)),
    (0, 'robot0', 1, 0, False, 'odom', (), ()),
    (0, 'robot0', 1, 2, False, 'odom', ('/base_scan_0', '/base_scan_1'),
     ('/base_laser_link_0', '/base_laser_link_1')),
    # one robot with -u: absolute, the model's own name
    (0, 'robot0', 1, 1, True, '/robot0/odom', ('/robot0/base_scan',),
     ('/robot0/base_laser_link',)),
    (0, 'robot0', 1, 2, True, '/robot0/odom', ('/robot0/base_scan_0', '/robot0/base_scan_1'),
     ('/robot0/base_laser_link_0', '/robot0/base_laser_link_1')),
    # one robot with -u but no name of its own (none, or Stage's token with a colon)
    (0, '', 1, 1, True, '/robot_0/odom', ('/robot_0/base_scan',),
     ('/robot_0/base_laser_link',)),
    (0, 'position:0', 1, 2, True, '/robot_0/odom', ('/robot_0/base_scan_0', '/robot_0/base_scan_1'),
     ('/robot_0/base_laser_link_0', '/robot_0/base_laser_link_1')),
    # several robots, no -u: /robot_<N>/ whatever the model is called
    (2, 'robot2', 4, 1, False, '/robot_2/odom', ('/robot_2/base_scan',),
     ('/robot_2/base_laser_link',)),
    (0, 'r', 2, 0, False, '/robot_0/odom', (), ()),
    (1, 'r', 2, 2, False, '/robot_1/odom', ('/robot_1/base_scan_0', '/robot_1/base_scan_1'),
     ('/robot_1/base_laser_link_0', '/robot_1/base_laser_link_1')),
    # several robots with -u
    (3, 'robot3', 4, 1, True, '/robot3/odom', ('/robot3/base_scan',),
     ('/robot3/base_laser_link',)),
    (1, 'position:1', 2, 1, True, '/robot_1/odom', ('/robot_1/base_scan',),
     ('/robot_1/base_laser_link',)),
    (1, 'b', 2, 2, True, '/b/odom', ('/b/base_scan_0', '/b/base_scan_1'),
     ('/b/base_laser_link_0', '/b/base_laser_link_1')),
]


@pytest.mark.parametrize('index, model, count, rangers, umn, odom, scans, frames', NAME_CASES)
def test_map_name_cases(index, model, count, rangers, umn, odom, scans, frames):
    n = robot_names(index, model, count, rangers, use_model_names=umn)
    p = odom[:-len('odom')]
    assert (n.cmd_vel, n.odom, n.ground_truth, n.stall) == \
        (p + 'cmd_vel', odom, p + 'base_pose_ground_truth', p + 'stall')
    assert (n.odom_frame, n.footprint_frame, n.base_frame) == \
        (odom, p + 'base_footprint', p + 'base_link')
    assert (n.scans, n.laser_frames) == (scans, frames)


@pytest.mark.parametrize('index, model, count, rangers, umn, odom, scans, frames', NAME_CASES)
def test_tf2_frames_only_drop_the_leading_slash_of_frames(index, model, count, rangers, umn,
                                                          odom, scans, frames):
    n = robot_names(index, model, count, rangers, use_model_names=umn, tf2_frames=True)
    assert (n.odom, n.scans) == (odom, scans)  # topics unchanged
    assert n.odom_frame == odom.lstrip('/')
    assert n.laser_frames == tuple(f.lstrip('/') for f in frames)
    assert not any(f.startswith('/') for f in (n.footprint_frame, n.base_frame))


@pytest.mark.parametrize('args', [(-1, 'r', 2, 1), (2, 'r', 2, 1), (0, 'r', 0, 1), (0, 'r', 1, -1)])
def test_impossible_robots_raise(args):
    with pytest.raises(ValueError):
        robot_names(*args)


def test_model_names_that_clash_are_reported():
    names = all_robot_names(['a', 'b', 'a'], [1, 1, 1], use_model_names=True)
    assert [n.odom for n in names] == ['/a/odom', '/b/odom', '/a/odom']
    lines = shared_namespaces(names)
    assert len(lines) == 1 and 'robots 0 and 2' in lines[0]
    assert shared_namespaces(all_robot_names(['a', 'b'], [1, 1])) == []
