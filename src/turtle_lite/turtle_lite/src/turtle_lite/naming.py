"""turtlesim's name counter (no rospy); name validation is course_common.graph_names."""


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
