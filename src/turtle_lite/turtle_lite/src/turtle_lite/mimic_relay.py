"""mimic's relay rules (no ROS): which topics it connects, and the pose -> command copy.

Mirrors turtlesim's mimic (tutorials/mimic.cpp); the node in mimic.py subscribes and publishes.
"""


from course_common.finite import check_finite
from course_common.graph_names import validate_graph_name

from turtle_lite.namespaces import append, remap, resolve_mappings, turtle_namespace

INPUT_NS = "input"
OUTPUT_NS = "output"


def mimic_topics(namespace, node_name, mappings):
    """Full names of (input/pose, output/cmd_vel), resolved as roscpp's NodeHandles do.

    turtlesim's mimic creates NodeHandles "input" and "output", so a remap of the namespace
    itself (`input:=turtlesim1/turtle1`) moves the topics under it (roscpp's namespace
    resolution, namespaces.py).
    namespace is the node's namespace, node_name its full name, mappings the command-line
    from:=to pairs. Raises ValueError for an invalid remapped name.
    """
    table = resolve_mappings(mappings, namespace, node_name)
    pose = remap(append(turtle_namespace(INPUT_NS, namespace, node_name, mappings), "pose"),
                 table)
    cmd_vel = remap(
        append(turtle_namespace(OUTPUT_NS, namespace, node_name, mappings), "cmd_vel"), table)
    # roscpp refuses an invalid remapped name at start-up; rospy would quietly use it.
    validate_graph_name(pose)
    validate_graph_name(cmd_vel)
    return pose, cmd_vel


def pose_to_command(linear_velocity, angular_velocity):
    """(linear_x, angular_z) for the follower: a copy of the leader's reported velocities.

    turtlesim's linear_velocity is a magnitude (never negative), so a reversing leader makes a
    forward-moving follower; that quirk is turtlesim's and is kept. Raises ValueError on a
    non-finite value (it would only poison the follower).
    """
    return (check_finite("linear_velocity", linear_velocity),
            check_finite("angular_velocity", angular_velocity))
