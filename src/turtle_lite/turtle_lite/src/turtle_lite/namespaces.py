"""Where a turtle's topics and services live: roscpp NodeHandle resolution (no rospy).

turtlesim gives each turtle ``ros::NodeHandle(name)`` and creates its six resources relative
to it (turtle.cpp's Turtle constructor). roscpp resolves that namespace like this:

1. a name starting with ``~`` is first resolved against the node name and remapped;
2. the name is validated; a relative name is appended to the node's namespace; the result is
   cleaned (``//`` collapsed, trailing ``/`` dropped);
3. the resolved namespace is looked up in the node's remapping table, so
   ``/turtle1:=/robot1`` moves the whole namespace;
4. each resource name is appended to that namespace, cleaned and looked up once more.

rospy only remaps exact full names, so a rospy node has to do this itself.
"""

from course_common.graph_names import validate_graph_name

#: The per-turtle resources, in turtlesim's order of creation.
TURTLE_TOPICS = ('cmd_vel', 'pose', 'color_sensor')
TURTLE_SERVICES = ('set_pen', 'teleport_relative', 'teleport_absolute')
TURTLE_RESOURCES = TURTLE_TOPICS + TURTLE_SERVICES


def clean(name):
    """roscpp ``names::clean``: collapse ``//`` and drop one trailing ``/`` (but keep ``/``)."""
    while '//' in name:
        name = name.replace('//', '/')
    if len(name) > 1 and name.endswith('/'):
        name = name[:-1]
    return name


def append(left, right):
    """roscpp ``names::append``."""
    return clean(left + '/' + right)


def node_namespace(node_name):
    """Namespace of a fully resolved node name: ``/g1/sim`` -> ``/g1``, ``/turtlesim`` -> ``/``."""
    parent = node_name.rstrip('/').rsplit('/', 1)[0]
    return parent or '/'


def resolve(name, namespace, node_name):
    """Resolve ``name`` to a full name without remapping (roscpp ``names::resolve(.., false)``)."""
    if not name:
        return clean('/' + namespace) if namespace else '/'
    if name[0] == '~':
        name = append(node_name, name[1:])
    if name[0] != '/':
        name = append('/', append(namespace, name))
    return clean(name)


def resolve_mappings(mappings, namespace, node_name):
    """Resolve both sides of command-line ``from:=to`` pairs the way roscpp's init does.

    Keys starting with ``__`` (``__name``, ``__log``, ...) and ``_param`` assignments are
    skipped. Already-resolved tables (rospy's ``get_resolved_mappings()``) pass unchanged.
    """
    table = {}
    for src, dst in mappings.items():
        if not src or not dst or src.startswith('_'):
            continue
        table[resolve(src, namespace, node_name)] = resolve(dst, namespace, node_name)
    return table


def remap(name, table):
    """Look a full name up once in a resolved remapping table."""
    return table.get(name, name)


def turtle_namespace(turtle_name, namespace, node_name, mappings):
    """The full (remapped) namespace of turtle ``turtle_name``.

    ``namespace`` is the node's namespace (``/`` at the root), ``node_name`` its full name,
    ``mappings`` the command-line remappings (raw or resolved). Raises ValueError with
    roscpp's message for an invalid name.
    """
    validate_graph_name(turtle_name)
    table = resolve_mappings(mappings, namespace, node_name)
    ns = turtle_name
    if ns.startswith('~'):
        ns = remap(resolve(ns, namespace, node_name), table)
        validate_graph_name(ns)
    if not ns:
        return clean('/' + namespace)
    if ns[0] != '/':
        ns = append(namespace, ns)
        if ns[0] != '/':
            ns = '/' + ns
    return remap(clean(ns), table)


def turtle_resources(turtle_name, namespace, node_name, mappings):
    """Full names of the six resources of a turtle: dict resource -> full name.

    Example: turtle ``turtle1`` of node ``/turtlesim`` with ``{'/turtle1': '/robot1'}`` gives
    ``{'cmd_vel': '/robot1/cmd_vel', 'pose': '/robot1/pose', ...}``.
    """
    ns = turtle_namespace(turtle_name, namespace, node_name, mappings)
    table = resolve_mappings(mappings, namespace, node_name)
    return {res: remap(append(ns, res), table) for res in TURTLE_RESOURCES}
