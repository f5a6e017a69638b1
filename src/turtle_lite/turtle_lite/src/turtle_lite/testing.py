"""Test helpers of turtle_lite's own tests (the lessons' tests use course_common's).

The simulator's constants as a test checks them, recorders of a turtle's pose and colour
sensor, and turtle_teleop_key on a terminal of its own.
"""
from course_common.arena import SPAWN_M, WORLD_SIZE_M
from course_common.processes import ChildProcess
from course_common.testing.recorders import Recorder
from turtlesim.msg import Color, Pose

#: float32 pose fields compared to this tolerance.
POSE_TOL = 1e-5
CENTER = SPAWN_M  # turtle1's start, float32 (course_common.arena)
WORLD = WORLD_SIZE_M  # the arena's side (m): 500 px at 45 px/m, less one pixel
TELEOP_ARGV = ('rosrun', 'turtle_lite', 'turtle_teleop_key')


class PoseRecorder(Recorder):
    def __init__(self, topic='/turtle1/pose', keep=None):
        super().__init__(topic, Pose, keep)

    def wait_at_rest(self):
        return self.wait(lambda p: p.linear_velocity == 0 and p.angular_velocity == 0,
                         '%s at rest' % self.topic)


class ColorRecorder(Recorder):
    def __init__(self, topic='/turtle1/color_sensor'):
        super().__init__(topic, Color)

    def wait_rgb(self, rgb, what):
        return self.wait(lambda c: (c.r, c.g, c.b) == tuple(rgb), what)


def run_teleop(argv=TELEOP_ARGV, env=None):
    """turtle_teleop_key (or argv) started on a pseudo-terminal of its own: a ChildProcess
    whose send() types keys and terminal_lflags() shows the terminal's mode."""
    return ChildProcess(argv, env=env, terminal=True).start()
