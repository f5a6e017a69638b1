"""Turtle names: roscpp's graph-name validation and turtlesim's name counter (no rospy)."""


def _is_alpha(c):
    return ('a' <= c <= 'z') or ('A' <= c <= 'Z')


def _is_valid_char(c):
    return _is_alpha(c) or ('0' <= c <= '9') or c in '/_'


def graph_name_error(name):
    """roscpp's ``ros::names::validate`` message for ``name``, or None when it is valid.

    The texts are roscpp's, byte for byte (note the two spaces after the full stop), because
    turtlesim reports them to the client and the log (TURTLESIM.md 1.8). Only ASCII letters
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


class NameCounter:
    """turtlesim's generator of default names ``turtle<N>``.

    N = ++counter, repeated until the name is unused. The counter starts at 0, is never
    decremented (killed numbers are not reused) and only ``reset()`` sets it back to 0.
    """

    PREFIX = 'turtle'

    def __init__(self):
        self.counter = 0

    def next_name(self, taken):
        """The next free name; ``taken`` is a container of names in use."""
        while True:
            self.counter += 1
            name = '%s%d' % (self.PREFIX, self.counter)
            if name not in taken:
                return name

    def reset(self):
        self.counter = 0
