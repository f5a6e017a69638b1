"""Stage 4.3's ranger model (libstage/model_ranger.cc): its sensors and where their rays leave.

A ranger has no body of its own; each `sensor( )` in it has a pose in the ranger's frame, a
size, a range, a field of view, a number of samples and noise. A ray leaves from the sensor's
pose raised to half the transducer's height, turned to the first beam.
"""
from .models import Model, read_colour, read_pose
from .pose import pose_add
from .worldfile import WorldError

RANGER_SIZE = (0.15, 0.15, 0.2)       # ModelRanger: a SICK LMS
SENSOR_SIZE = (0.02, 0.02, 0.02)      # a ranger's transducer: its beam leaves at half height


class Sensor:
    """One `sensor( )` of a ranger: pose in the ranger's frame, size, range [min, max] (m),
    fov (rad), samples, noise (constant variance m^2, proportional, angle)."""

    def __init__(self):
        self.pose = (0.0, 0.0, 0.0, 0.0)
        self.size = SENSOR_SIZE
        self.range = (0.0, 5.0)
        self.fov = 0.1
        self.samples = 1
        self.noise = (0.0, 0.0, 0.0)
        self.where = None
        # what its last update read (the world points these into its beam arrays)
        self.ranges = None
        self.intensities = None
        # the world's beam array the ranges view, and where they start in it
        self.beams = None
        self.beam_at = 0

    def load(self, wf, e):
        self.where = (wf.entities[e].path, wf.entities[e].line)
        self.pose = read_pose(wf, e, 'pose', self.pose)
        self.size = tuple(wf.read_tuple(e, 'size', 'lll') or self.size)
        self.range = tuple(wf.read_tuple(e, 'range', 'll') or self.range)
        self.fov = wf.read_angle(e, 'fov', self.fov)
        self.samples = wf.read_int(e, 'samples', self.samples)
        self.noise = tuple(wf.read_tuple(e, 'noise', 'lfa') or self.noise)
        read_colour(wf, e, (0.0, 0.0, 1.0, 0.15))
        p = wf.prop(e, 'samples')
        if self.samples < 1:
            raise WorldError(p.path if p else self.where[0], p.line if p else self.where[1],
                             'samples must be at least 1, got %d' % self.samples)


class Ranger(Model):
    """ModelRanger: no body of its own, its `sensor( )`s."""

    def construct(self):
        self.color = (0.0, 0.0, 0.5, 1.0)
        self.clear_blocks()
        self.set_geom((0.0, 0.0, 0.0, 0.0), RANGER_SIZE)
        self.sensors = []

    def load_sensor(self, wf, e):
        s = Sensor()
        s.load(wf, e)
        self.sensors.append(s)

    def ray_origin(self, sensor):
        """The first ray's pose (x, y, z, a) in the world, as Sensor::Update makes it: the
        sensor's pose, turned to the first beam, raised to half the transducer's height."""
        return pose_add(self.body_pose(), self.ray_local(sensor))

    def ray_origins(self):
        """ray_origin of each of its sensors, in order (its body's pose found once)."""
        body = self.body_pose()
        return [pose_add(body, self.ray_local(s)) for s in self.sensors]

    @staticmethod
    def ray_local(sensor):
        """The first ray's pose in the ranger's body frame."""
        x, y, z, a = sensor.pose
        start = -sensor.fov / 2.0 if sensor.samples > 1 else 0.0
        return (x, y, z + sensor.size[2] / 2.0, a + start)

    @staticmethod
    def sample_increment(sensor):
        return sensor.fov / max(sensor.samples - 1, 1)
