"""ROS graph resource names: roscpp's validation messages and namespace normalisation (no rospy)."""


def _is_alpha(c):
    return ('a' <= c <= 'z') or ('A' <= c <= 'Z')


def _is_valid_char(c):
    return _is_alpha(c) or ('0' <= c <= '9') or c in '/_'


def graph_name_error(name):
    """roscpp's ``ros::names::validate`` message for ``name``, or None when it is valid.

    The texts are roscpp's, byte for byte (note the two spaces after the full stop), because
    turtlesim reports them to the client and the log (turtle_frame.cpp's spawn). Only ASCII letters
    and digits count, as with C's isalpha/isalnum in the "C" locale.
    """
    if not name:
        return None
    c = name[0]
    if not _is_alpha(c) and c not in '/~':
        return ('Character [%s] is not valid as the first character in Graph Resource Name '
                '[%s].  Valid characters are a-z, A-Z, / and in some cases ~.' % (c, name))
    for i in range(1, len(name)):
        c = name[i]
        if not _is_valid_char(c):
            return ('Character [%s] at element [%d] is not valid in Graph Resource Name [%s].  '
                    'Valid characters are a-z, A-Z, 0-9, / and _.' % (c, i, name))
    return None


def validate_graph_name(name):
    """Raise ValueError with roscpp's message if ``name`` is not a valid graph resource name."""
    error = graph_name_error(name)
    if error is not None:
        raise ValueError(error)


def normalize_namespace(namespace):
    """'/', '/sim', 'sim/', ... as an absolute namespace ending in '/'. Raises ValueError."""
    if not isinstance(namespace, str):
        raise ValueError('namespace %r: expected a string such as / or /sim' % (namespace,))
    ns = '/' + namespace.strip().strip('/')
    return ns if ns == '/' else ns + '/'
