#!/usr/bin/env python3
"""stageros -u with the extras switched on: model names, tf2 frames, stall, /map, pictures."""
import os
import tempfile

import numpy as np
import rospy
import rostest
from course_common.testing.recorders import stamp_ns
from course_msgs.srv import SaveImage
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import OccupancyGrid, Odometry
from PIL import Image
from stage_support import (
    EVENT_DEADLINE_S,
    START_DEADLINE_S,
    Recorder,
    StageTestCase,
    topic_types,
    wait_connected,
    wait_for,
)
from std_msgs.msg import Bool
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

MODELS = ('robot0', 'robot1', 'robot2', 'robot3')
DRIVE_MPS = 0.5
CMD_PERIOD_S = 0.05  # wall s between commands: well inside the 1 s watchdog at 4 x real time
WATCHDOG_NS = 1_000_000_000  # ~base_watchdog_timeout in stageros_extras.test
STEP_NS = 100_000_000
TURN_RADPS = 0.3
#: A load spike longer than the watchdog (0.25 s of wall time at 4 x) stops every robot; the
#: shared-watchdog test then commands again, at most this many times.
WATCHDOG_ATTEMPTS = 3


class StagerosExtrasTest(StageTestCase):
    NODE_NAME = 'stageros_extras_test'

    def test_model_names_as_namespaces(self):
        def published():
            types = topic_types()
            return types if '/robot3/base_scan' in types else None
        types = wait_for(published, START_DEADLINE_S, 'the -u topics')
        for m in MODELS:
            self.assertEqual(types['/%s/odom' % m], 'nav_msgs/Odometry')
            self.assertEqual(types['/%s/stall' % m], 'std_msgs/Bool')
        self.assertFalse([t for t in types if t.startswith('/robot_')])

    def test_tf2_frames_and_odom_child_frame(self):
        rec = Recorder('/tf', TFMessage, keep=1)
        pairs = {(t.header.frame_id, t.child_frame_id) for t in rec.wait_first().transforms}
        rec.close()
        for m in MODELS:
            self.assertIn((m + '/odom', m + '/base_footprint'), pairs)
            self.assertIn((m + '/base_link', m + '/base_laser_link'), pairs)
        self.assertFalse([f for pair in pairs for f in pair if f.startswith('/')])
        odom = Recorder('/robot1/odom', Odometry, keep=1)
        truth = Recorder('/robot1/base_pose_ground_truth', Odometry, keep=1)
        self.assertEqual(odom.wait_first().header.frame_id, 'robot1/odom')
        self.assertEqual(odom.wait_first().child_frame_id, 'robot1/base_footprint')
        self.assertEqual(truth.wait_first().child_frame_id, '')

    def test_map_and_its_frame_above_every_odom(self):
        grid = Recorder('/map', OccupancyGrid).wait_first()
        self.assertEqual(grid.header.frame_id, 'map')
        cells = np.asarray(grid.data, dtype=np.int8).reshape(grid.info.height, grid.info.width)
        self.assertEqual(set(np.unique(cells)), {0, 100})
        # The room's east wall (x = 4) is in the last columns, its middle free.
        col = int((3.98 - grid.info.origin.position.x) / grid.info.resolution)
        row = int((0.0 - grid.info.origin.position.y) / grid.info.resolution)
        self.assertEqual(cells[row, col], 100)
        self.assertEqual(cells[row, col - int(1.0 / grid.info.resolution)], 0)
        static = Recorder('/tf_static', TFMessage).wait_first()
        self.assertEqual({(t.header.frame_id, t.child_frame_id) for t in static.transforms},
                         {('map', m + '/odom') for m in MODELS})

    def test_stall_goes_true_at_the_wall_and_back_to_false_on_reset(self):
        stall = Recorder('/robot0/stall', Bool)
        self.assertIs(stall.wait_first().data, False)
        odom = Recorder('/robot0/odom', Odometry, keep=1)
        pub = rospy.Publisher('/robot0/cmd_vel', Twist, queue_size=10)
        wait_connected(pub, 'robot0/cmd_vel')

        def drive_until_stalled():
            pub.publish(Twist(linear=Vector3(DRIVE_MPS, 0, 0)))
            return stall.latest().data
        wait_for(drive_until_stalled, EVENT_DEADLINE_S, 'robot0 stalled at the east wall',
                 poll_s=CMD_PERIOD_S)
        self.assertEqual([m.data for m in stall.messages()], [False, True], 'on change only')
        x = odom.latest().pose.pose.position.x
        self.assertGreater(x, 3.5)
        self.assertAlmostEqual(odom.latest().twist.twist.linear.x, DRIVE_MPS, delta=1e-9,
                               msg='odom keeps the commanded twist while stalled')
        rospy.ServiceProxy('/reset_positions', Empty)()
        wait_for(lambda: stall.latest().data is False, EVENT_DEADLINE_S, 'the stall cleared')
        stall.close()
        odom.close()

    def test_one_watchdog_time_for_every_robot(self):
        # stageros keeps one time of the last cmd_vel for all robots: robot1, commanded once,
        # keeps turning while robot2 gets commands, and stops once nobody commands anything.
        odom = Recorder('/robot1/odom', Odometry)
        turn = rospy.Publisher('/robot1/cmd_vel', Twist, queue_size=10)
        other = rospy.Publisher('/robot2/cmd_vel', Twist, queue_size=10)
        wait_connected(turn, 'robot1/cmd_vel')
        wait_connected(other, 'robot2/cmd_vel')
        odom.wait_first()
        kept_turning = False
        for _ in range(WATCHDOG_ATTEMPTS):
            odom.clear()
            turn.publish(Twist(angular=Vector3(0, 0, TURN_RADPS)))
            moving = odom.wait_where(lambda m: m.twist.twist.angular.z > 0, 'the turn')
            # Without the shared time robot1 reads 0 at moving + watchdog + 1 step.
            beyond_ns = stamp_ns(moving) + WATCHDOG_NS + 5 * STEP_NS

            def settled(beyond_ns=beyond_ns):
                other.publish(Twist())
                last = odom.latest()
                if last.twist.twist.angular.z == 0 or stamp_ns(last) >= beyond_ns:
                    return last
                return None
            last = wait_for(settled, EVENT_DEADLINE_S, 'robot1 past its own watchdog time',
                            poll_s=CMD_PERIOD_S)
            if last.twist.twist.angular.z == TURN_RADPS:
                kept_turning = True
                break
        self.assertTrue(kept_turning, 'robot1 stopped while robot2 was being commanded')
        stopped = odom.wait_where(lambda m: stamp_ns(m) > stamp_ns(last)
                                  and m.twist.twist.angular.z == 0, 'robot1 stopped')
        self.assertGreater(stamp_ns(stopped), stamp_ns(last))
        rospy.ServiceProxy('/reset_positions', Empty)()
        odom.close()

    def test_save_image_draws_the_robots_in_their_colours(self):
        rospy.wait_for_service('/stageros/save_image', timeout=START_DEADLINE_S)
        path = os.path.join(tempfile.mkdtemp(prefix='stage_extras_'), 'sub', 'world.png')
        written = rospy.ServiceProxy('/stageros/save_image', SaveImage)(path).path
        self.assertEqual(written, path)
        pixels = np.asarray(Image.open(path).convert('RGB')).reshape(-1, 3)
        colours = {tuple(p) for p in np.unique(pixels, axis=0)}
        for rgb in ((0, 0, 255), (255, 0, 0), (0, 255, 0), (255, 0, 255), (77, 77, 77)):
            self.assertIn(rgb, colours)


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_extras', StagerosExtrasTest)
