"""What convoy_demo and the convoy bench launch: the convoy's launch arguments and its nodes.

They run it with course_common.private_launch.PrivateMasterLaunch (its own master on a free
port) and record it with convoy.recording's rosbag recorder.
"""

POLL_S = 0.05  # condition polling period (wait_for's poll_s): the harness waits for seconds


class HarnessError(RuntimeError):
    """The launch could not be started or did not reach an expected state."""


def launch_for(n_robots, gui=False, markers=False):
    """roslaunch arguments for an autopilot convoy of n_robots (the course file for 3).

    markers: also tf and what the rviz view draws (the demo's rviz picture).
    """
    extra = ['gui:=%s' % ('true' if gui else 'false')] + (['markers:=true'] if markers else [])
    if n_robots == 3:
        return ['convoy', 'convoy.launch', 'autopilot:=true'] + extra
    return ['convoy', 'convoy_chain.launch', 'n:=%d' % n_robots, 'autopilot:=true'] + extra


def convoy_node_names(n_robots):
    """Names of the convoy_node instances of launch_for(n_robots), follower 2 first."""
    if n_robots == 3:
        return ['/convoy_node', '/convoy2_node']
    return ['/convoy_robot%d' % i for i in range(2, n_robots + 1)]
