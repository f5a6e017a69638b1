"""Stage's plugin interface in Python, its sensors: a ranger's sensors, a fiducial finder's
readings and a blobfinder's blobs as a controller sees them (stage_api's handles, made by
stage_api.api_of). No rospy.
"""
from dataclasses import replace

from .fiducial import last_nearest_of
from .stage_api import ModelApi, Pose, api_of


class SensorApi:
    """One sensor of a ranger (Stage's ModelRanger::Sensor): pose, size, range, fov,
    sample_count, and what its last update read (ranges, intensities: arrays, writable, as
    a lasernoise-like controller changes them; bearings)."""

    def __init__(self, sensor):
        self._sensor = sensor

    pose = property(lambda self: Pose(*self._sensor.pose))
    size = property(lambda self: tuple(self._sensor.size))
    range = property(lambda self: tuple(self._sensor.range))
    fov = property(lambda self: self._sensor.fov)
    sample_count = property(lambda self: self._sensor.samples)
    ranges = property(lambda self: self._sensor.ranges)
    intensities = property(lambda self: self._sensor.intensities)

    def first_range_at(self):
        """(array, index): where ranges[0] lives (the world's beam array), for a
        controller's batch that reads many sensors in one kernel; None for a sensor the
        world does not cast."""
        s = self._sensor
        return None if s.beams is None else (s.beams, s.beam_at)

    @property
    def bearings(self):
        s = self._sensor
        start = -s.fov / 2.0 if s.samples > 1 else 0.0
        incr = s.fov / max(s.samples - 1, 1)
        return [start + t * incr for t in range(s.samples)]


class RangerApi(ModelApi):
    """Stage's ModelRanger: its sensors."""

    @property
    def sensors(self):
        return [SensorApi(s) for s in self._model.sensors]

    def get_sensors(self):
        return self.sensors


class FiducialApi(ModelApi):
    """Stage's ModelFiducial: `fiducials`, what its last update saw (each with `range`,
    `bearing`, `geom` (his size x, y, z, his heading relative to the finder's), `pose` (his
    global pose), `id`, and `model`, him as a controller sees him)."""

    @property
    def fiducials(self):
        return [replace(f, model=api_of(self._world, f.model))
                for f in getattr(self._model, 'fiducials', [])]

    def get_fiducials(self):
        return self.fiducials

    def seen_count(self):
        """len(fiducials), without making them (for a controller's batch)."""
        return self._model.seen_count()

    def nearest(self):
        """(range, his heading relative to the finder's) of the first of the readings of
        the least range, or None when it saw nothing: min(fiducials, by range), without
        making the readings."""
        return self._model.nearest()

    def read_nearest_only(self):
        """This finder's readings are read by nearest() only (a controller that says so):
        its updates may then find the nearest alone, skipping the rays to the others (what
        it sees is the same; asked for, the readings are made as the update would have, in
        the step of that update). Not when your own controllers run: every finder makes
        all its readings then."""
        self._model.nearest_only = True

    @staticmethod
    def nearest_rows(handles):
        """The handles' finders' nearest() at once, as rows (range, heading, found), when
        one update made them all (fiducial.last_nearest_of), else None: for a controller's
        batch."""
        return last_nearest_of([h._model for h in handles])


class BlobfinderApi(ModelApi):
    """Stage's ModelBlobfinder: `blobs`, what its last update saw (colour, left, top, right,
    bottom, range)."""

    @property
    def blobs(self):
        return list(getattr(self._model, 'blobs', []))

    def get_blobs(self):
        return self.blobs
