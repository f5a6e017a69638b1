"""turtlesim_node's tick thread: a function called on absolute deadlines, like a Qt timer."""
import time

from course_common.deadline_loop import DeadlineLoop
from course_common.schedule import Deadlines


class TickLoop(DeadlineLoop):
    """Calls tick() every period_s seconds on deadlines that do not drift, in its own thread.

    The first tick comes one period after start. An exception from tick() is logged
    (throttled) and the loop goes on, unless the loop was stopped or ROS is shutting down,
    which ends it.
    """

    def __init__(self, tick, period_s, name):
        super().__init__(tick, lambda: Deadlines(period_s, time.monotonic() + period_s),
                         name, 'turtlesim tick', stop_at_shutdown=False)
