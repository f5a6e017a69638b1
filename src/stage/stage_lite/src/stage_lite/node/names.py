"""Topic and frame names of stageros's robots, as stage_ros 1.8.0 makes them (pure, no rospy).

stageros's mapName(): with more than one robot, or with ``-u``, every name is absolute:
``/robot_<N>/<name>``, or ``/<model name>/<name>`` with ``-u`` when the model has a name
(a name Stage made up, ``position:0``, has a colon and falls back to ``robot_<N>``). With
one robot and no ``-u`` the names are relative (``odom``, ``base_scan``), so the node's
namespace applies. Several rangers on one robot are ``base_scan_<k>`` and
``base_laser_link_<k>``, and these per-device names are always absolute: with one robot and
no ``-u`` they are ``/base_scan_<k>`` and ``/base_laser_link_<k>`` (mapName's device form puts
a '/' before them even when the robot's other names are relative). Frame ids are the same
strings (the leading '/' that tf2 rejects, stage_ros #68/#69); tf2_frames=True drops it, the
opt-in fix. The laser frames hang on base_link in the tf tree.
"""
from dataclasses import dataclass


@dataclass(frozen=True)
class RobotNames:
    """One robot's graph names (topics, service-free) and frame ids."""

    cmd_vel: str
    odom: str
    ground_truth: str
    stall: str
    scans: tuple          # one topic per ranger
    odom_frame: str
    footprint_frame: str
    base_frame: str
    laser_frames: tuple   # one frame per ranger


def prefix(index, model_name, robot_count, use_model_names):
    """'' (relative names) or the absolute '/<ns>/' that stageros puts before each name."""
    if robot_count <= 1 and not use_model_names:
        return ''
    if use_model_names and model_name and ':' not in model_name:
        return '/%s/' % model_name
    return '/robot_%d/' % index


def frame_id(name, tf2_frames):
    """A frame id as stageros sends it (a leading `/`), or tf2's without it."""
    return name.lstrip('/') if tf2_frames else name


def robot_names(index, model_name, robot_count, ranger_count, use_model_names=False,
                tf2_frames=False):
    """RobotNames of robot ``index`` (0-based, world-file order) with ``ranger_count`` rangers."""
    if index < 0 or robot_count < 1 or index >= robot_count or ranger_count < 0:
        raise ValueError('robot %d of %d with %d rangers is not a robot'
                         % (index, robot_count, ranger_count))
    p = prefix(index, model_name, robot_count, use_model_names)
    if ranger_count == 1:
        scans = (p + 'base_scan',)
        lasers = (p + 'base_laser_link',)
    else:
        device_prefix = p or '/'  # per-device names are absolute even for one robot
        scans = tuple('%sbase_scan_%d' % (device_prefix, k) for k in range(ranger_count))
        lasers = tuple('%sbase_laser_link_%d' % (device_prefix, k) for k in range(ranger_count))
    return RobotNames(
        cmd_vel=p + 'cmd_vel', odom=p + 'odom', ground_truth=p + 'base_pose_ground_truth',
        stall=p + 'stall', scans=scans,
        odom_frame=frame_id(p + 'odom', tf2_frames),
        footprint_frame=frame_id(p + 'base_footprint', tf2_frames),
        base_frame=frame_id(p + 'base_link', tf2_frames),
        laser_frames=tuple(frame_id(f, tf2_frames) for f in lasers))


def all_robot_names(model_names, ranger_counts, use_model_names=False, tf2_frames=False):
    """RobotNames of every robot, in world-file order."""
    count = len(model_names)
    return [robot_names(i, m, count, r, use_model_names, tf2_frames)
            for i, (m, r) in enumerate(zip(model_names, ranger_counts, strict=True))]


def shared_namespaces(names):
    """One line per robot whose names another robot already uses (-u with two equal names).

    stageros lets them share their topics; the node warns, as their messages will mix.
    """
    first = {}
    lines = []
    for i, n in enumerate(names):
        if n.odom in first:
            lines.append('robots %d and %d share the namespace of %s: their topics will mix'
                         % (first[n.odom], i, n.odom))
        else:
            first[n.odom] = i
    return lines
