"""The lessons split over hosts: which command runs where, and the start sequence.

Per-host launch instead of roslaunch's <machine> tag: <machine> starts remote nodes over ssh
(keys, known_hosts, and an env-loader script on every robot), which the namespaces here, and
many lab networks, do not have; a roslaunch per host needs only ROS_MASTER_URI and ROS_IP.
"""
from course_common.waiting import wait_for

from multihost.harness import Probe

MULTI_SYNC_ROBOTS = ['robot_0', 'robot_1', 'robot_2', 'robot_3']
# multi_sync's two simulators: the lesson's Stage (multi_sync.launch) and turtlesim
# (multi_sync_turtlesim.launch); the robots' launch is the same on both.
TURTLESIM, STAGE = 'turtlesim', 'stage'
MULTI_SYNC_SIM_LAUNCH = {TURTLESIM: 'multi_sync_turtlesim.launch', STAGE: 'multi_sync.launch'}
CONVOY_ROBOTS = ['robot1', 'robot2', 'robot3']
# The lesson's layout across three hosts; ONE_HOST puts every role on host 1.
MULTI_SYNC_HOSTS = {'sim': 1, 'monitor': 1, 'robots_01': 2, 'robots_23': 3}
CONVOY_HOSTS = {'sim': 1, 'convoy_node': 2, 'convoy2_node': 3}
# A Stage swarm: stageros on host 1, its robots split between a controller on host 2 and one
# on host 3.
SWARM_HOSTS = {'sim': 1, 'swarm_a': 2, 'swarm_b': 3}
STARTUP_S = 60.0  # master, simulator and nodes starting on a loaded 2-core machine


def one_host(layout):
    return dict.fromkeys(layout, 1)


def start_master(team, robots, status=False, pose_period_s=0.1, stage=False):
    """roscore on host 1 and a probe there; returns the probe once the master answers it."""
    team.start('roscore', 1, ['roscore', '-p', '11311'])
    args = ['--robots', *robots, '--pose-period', str(pose_period_s)]
    args += (['--status'] if status else []) + (['--stage'] if stage else [])
    probe = Probe(team, 'probe', 1, args)
    wait_for(probe.ready, STARTUP_S, 'the master on host 1 to answer the probe (%s)'
             % team.log_path('roscore'))
    return probe


def start_roscore(team):
    """roscore on host 1, once it answers (roslaunch would start a master of its own)."""
    team.start('roscore', 1, ['roscore', '-p', '11311'])
    wait_for(lambda: team.run(1, ['rosparam', 'get', '/rosdistro'])[0] == 0, STARTUP_S,
             'the master on host 1 (%s)' % team.log_path('roscore'))


def start_multi_sync(team, layout=None, simulator=TURTLESIM):
    """The lesson: simulator, robots 0-1, robots 2-3, then (once all are ready) the monitor.

    On Stage the probe prints every pose (Stage's 10 Hz steps; turtlesim's 62.5 Hz poses are
    thinned to 10 Hz) and stageros runs headless, as on a robot lab's master without a screen.
    """
    layout = layout or MULTI_SYNC_HOSTS
    stage = simulator == STAGE
    probe = start_master(team, MULTI_SYNC_ROBOTS, status=True, stage=stage,
                         pose_period_s=0.0 if stage else 0.1)
    team.start('sim', layout['sim'],
               ['roslaunch', 'multi_sync', MULTI_SYNC_SIM_LAUNCH[simulator], 'robots:=false'],
               extra_env={'DISPLAY': None} if stage else None)
    team.start('robots_01', layout['robots_01'],
               ['roslaunch', 'multi_sync', 'robots.launch', 'id:=0', 'team_size:=2'])
    team.start('robots_23', layout['robots_23'],
               ['roslaunch', 'multi_sync', 'robots.launch', 'id:=2', 'team_size:=4'])
    wait_for(lambda: {e['id'] for e in probe.events('status')} >= {0, 1, 2, 3}, STARTUP_S,
             'ready reports of robots 0-3 on team_status')
    team.start('monitor', layout['monitor'], ['rosrun', 'multi_sync', 'monitor', '4'])
    return probe


def start_convoy(team, layout=None, pose_period_s=0.1):
    """convoy.launch's simulator and autopilot on host 1, one convoy_node per follower host."""
    layout = layout or CONVOY_HOSTS
    probe = start_master(team, CONVOY_ROBOTS, pose_period_s=pose_period_s)
    team.start('sim', layout['sim'], ['roslaunch', 'convoy', 'convoy.launch', 'followers:=false',
                                      'autopilot:=true'])
    team.start('convoy_node', layout['convoy_node'],
               ['roslaunch', 'convoy', 'convoy_follower.launch', 'name:=convoy_node',
                'leader:=robot1', 'follower:=robot2'])
    team.start('convoy2_node', layout['convoy2_node'],
               ['roslaunch', 'convoy', 'convoy_follower.launch', 'name:=convoy2_node',
                'leader:=robot2', 'follower:=robot3'])
    return probe


def start_swarm(team, robots, layout=None, speedup=1.0, probe=True):
    """swarm.launch's stageros (no controller) on the layout's sim host and the robots split
    between the layout's controllers (swarm_a's the first half, swarm_b's the rest; a layout
    whose swarm_b is None: swarm_a drives them all); a probe on host 1 printing every
    robot's ground-truth pose (probe False: none, and None returned)."""
    layout = layout or SWARM_HOSTS
    names = ['robot_%d' % i for i in range(robots)]
    watcher = start_master(team, names, stage=True) if probe else start_roscore(team)
    team.start('sim', layout['sim'],
               ['roslaunch', 'swarm', 'swarm.launch', 'robots:=%d' % robots,
                'controller:=false', 'speedup:=%g' % speedup], extra_env={'DISPLAY': None})
    half = robots // 2 if layout.get('swarm_b') else robots
    for name, first, count in (('swarm_a', 0, half), ('swarm_b', half, robots - half)):
        if count:
            team.start(name, layout[name],
                       ['rosrun', 'swarm', 'swarm_controller', '__name:=' + name,
                        '_first:=%d' % first, '_robots:=%d' % count])
    return watcher
