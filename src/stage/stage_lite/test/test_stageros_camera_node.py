#!/usr/bin/env python3
"""stageros's cameras as a user sees them (node_camera.world): topics, types, encodings,
sizes, frames, rates in sim time, the camera's transform and the depth of a wall."""
import math

import numpy as np
import rostest
from course_common.testing.recorders import stamp_ns
from sensor_msgs.msg import CameraInfo, Image
from stage_lite.model.camera_render import SAMPLE_Y
from stage_support import (
    EVENT_DEADLINE_S,
    START_DEADLINE_S,
    STEP_NS,
    Recorder,
    StageTestCase,
    topic_types,
    wait_for,
)
from tf2_msgs.msg import TFMessage

ONE = '/robot_0/'
TWO = ('/robot_1/image_0', '/robot_1/image_1')
RUN_STEPS = 10
WALL_M = 1.95             # the east wall's face ahead of robot_0's centre, where Stage looks from
EYE_Z_M = 0.25            # the robot's height: the camera's base
WALL_TOP_M = 0.5
DEPTH_TOL_M = 1e-4        # float32 metres


def _pixels(msg, dtype, channels=1):
    shape = (msg.height, msg.width, channels) if channels > 1 else (msg.height, msg.width)
    return np.frombuffer(msg.data, dtype).reshape(shape)


class StagerosCameraTest(StageTestCase):
    NODE_NAME = 'stageros_camera_test'

    def test_topics_and_types(self):
        names = [ONE + 'image', ONE + 'depth', ONE + 'camera_info', *TWO,
                 '/robot_1/depth_0', '/robot_1/depth_1', '/robot_1/camera_info_0',
                 '/robot_1/camera_info_1']
        types = wait_for(lambda: (lambda t: t if all(n in t for n in names) else None)(
            topic_types()), START_DEADLINE_S, 'every camera topic')
        for n in names:
            self.assertEqual(types[n], 'sensor_msgs/CameraInfo' if 'camera_info' in n
                             else 'sensor_msgs/Image', n)
        self.assertNotIn('/robot_1/image', types)

    def test_image_depth_info_of_one_camera(self):
        image = Recorder(ONE + 'image', Image, keep=1).wait_first()
        self.assertEqual((image.encoding, image.width, image.height, image.step,
                          image.header.frame_id), ('rgba8', 32, 24, 128, ONE + 'camera'))
        depth = Recorder(ONE + 'depth', Image, keep=1).wait_first()
        self.assertEqual((depth.encoding, depth.width, depth.height, depth.step,
                          depth.header.frame_id), ('32FC1', 32, 24, 128, ONE + 'camera'))
        info = Recorder(ONE + 'camera_info', CameraInfo, keep=1).wait_first()
        self.assertEqual((info.width, info.height, info.header.frame_id),
                         (32, 24, ONE + 'camera'))
        fx = 32 / (2 * math.tan(math.radians(30)))
        fy = 24 / (2 * math.tan(math.radians(20)))
        self.assertEqual(list(info.K), [fx, 0, 16, 0, fy, 12, 0, 0, 1])
        self.assertEqual(list(info.P), [fx, 0, 16, 0, 0, fy, 12, 0, 0, 0, 1, 0])
        self.assertEqual(list(info.D), [0.0] * 4)

    def test_depth_reads_the_wall(self):
        depth = _pixels(Recorder(ONE + 'depth', Image, keep=1).wait_first(), '<f4')
        # each row's sample point (Stage's: not the pixel centre): the wall's foot is row 16
        tan_v = (1.0 - (np.arange(24) + SAMPLE_Y) / 12.0) * math.tan(math.radians(20))
        z = EYE_Z_M + WALL_M * tan_v
        wall = (z >= 0.0) & (z <= WALL_TOP_M)
        self.assertEqual(np.flatnonzero(wall).tolist(), list(range(8, 17)))
        # Stage's depth is along the view axis: the wall square to it reads its distance
        self.assertTrue(np.allclose(depth[wall], WALL_M, atol=DEPTH_TOL_M), depth[wall])
        self.assertTrue(np.isposinf(depth[0]).all(), 'above the walls: +inf (beyond far)')
        # the floor's near rows: Stage's polygon offset reads them deeper than they lie
        floor = np.zeros(24, bool)
        floor[-4:] = True
        self.assertTrue(np.isfinite(depth[floor]).all())
        self.assertTrue((depth[floor] > (-EYE_Z_M / tan_v[floor])[:, None]).all())
        image = _pixels(Recorder(ONE + 'image', Image, keep=1).wait_first(), np.uint8, 4)
        self.assertEqual(tuple(image[12, 16]), (0, 0, 255, 255))       # the blue wall
        self.assertEqual(tuple(image[-1, 16]), (255, 255, 255, 255))   # Stage's white floor

    def test_every_step_in_sim_time(self):
        recs = [Recorder(ONE + 'image', Image), Recorder(ONE + 'depth', Image),
                Recorder(ONE + 'camera_info', CameraInfo)]
        for rec in recs:
            wait_for(lambda r=rec: r.count() > RUN_STEPS + 2, EVENT_DEADLINE_S,
                     '%d messages on %s' % (RUN_STEPS + 2, rec.topic))
        for rec in recs:
            stamps = [stamp_ns(m) for m in rec.messages()][1:RUN_STEPS + 1]
            rec.close()
            self.assertTrue(all(s > 0 for s in stamps), rec.topic)
            self.assertEqual({b - a for a, b in zip(stamps, stamps[1:], strict=False)},
                             {STEP_NS}, '%s: one message per 0.1 s of sim time' % rec.topic)

    def test_two_cameras_device_names_and_sizes(self):
        for k, (w, h) in enumerate(((16, 12), (8, 6))):
            msg = Recorder(TWO[k], Image, keep=1).wait_first()
            self.assertEqual((msg.width, msg.height, msg.header.frame_id),
                             (w, h, '/robot_1/camera_%d' % k))

    def test_tf_hangs_the_camera_on_base_link(self):
        image = Recorder(ONE + 'image', Image, keep=1)   # the transform goes with the image
        image.wait_first()
        tf = Recorder('/tf', TFMessage).wait_where(
            lambda m: any(t.child_frame_id == ONE + 'camera' for t in m.transforms),
            'the camera transform')
        t = next(t for t in tf.transforms if t.child_frame_id == ONE + 'camera')
        image.close()
        self.assertEqual(t.header.frame_id, ONE + 'base_link')
        tr = t.transform.translation
        self.assertEqual((tr.x, tr.y), (0.1, 0.0))
        self.assertAlmostEqual(tr.z, EYE_Z_M, delta=1e-9)
        # stageros: setRPY(pitch - pi, 0, yaw): pitch 90 (no tilt), yaw -90 (no pan)
        roll, yaw = -math.pi / 2, -math.pi / 2
        want = (math.sin(roll / 2) * math.cos(yaw / 2), math.sin(roll / 2) * math.sin(yaw / 2),
                math.cos(roll / 2) * math.sin(yaw / 2), math.cos(roll / 2) * math.cos(yaw / 2))
        q = t.transform.rotation
        dot = abs(q.x * want[0] + q.y * want[1] + q.z * want[2] + q.w * want[3])
        self.assertAlmostEqual(dot, 1.0, delta=1e-9)


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_camera', StagerosCameraTest)
