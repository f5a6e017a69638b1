#!/usr/bin/env python3
"""multi_sync.launch map:=true: the Stage lesson in rviz/multi_sync.rviz, live and from a bag.

Live: rviz under Xvfb on the lesson's view while `rosbag record -a` records the run and the
test starts the monitor, as the lesson's student does; rviz subscribes to every topic of the
file, logs no error and shows the floor plan and each robot's laser scan in its colour. Then
the bag is played back (`rosbag play`, /use_sim_time true) into a fresh rviz on a fresh master
of the test's own, and rviz shows the map and the scans again. Screenshots of both go beside
the test's results (stage_rviz_live.png, stage_rviz_playback.png).
"""
import os
import sys

import rosbag
import rosgraph
import rospkg
import rospy
import rostest
from course_common.rviz.screen import (
    colour_pixels,
    error_lines,
    missing_colours,
    render_area,
)
from course_common.rviz.snapshot import RvizOnXvfb
from course_common.testing import ChildProcess, ScratchDirTestCase, results_dir, wait_for
from course_common.testing.master import Roscore, subscribers_of
from PIL import Image
from stage_watch import StageWatch
from team_watch import NodeProcess

ROBOTS = 4
RVIZ_DEADLINE_S = 180.0  # rviz with software GL, twice, on a loaded 2-core machine
START_DEADLINE_S = 90.0  # stageros, four robots, the monitor, rosbag: Python start-ups
DRIVE_DEADLINE_S = 120.0  # the back pair drives 2.4 m at the lesson's 0.2 m/s
BAG_CLOSE_DEADLINE_S = 30.0  # rosbag record writes its index on SIGINT
PLAY_DEADLINE_S = 180.0  # the run again at its own pace (rosbag play follows the bag's time)
RECORDER = 'stage_views_record'

# What rviz/multi_sync.rviz draws. The floor plan's free cells: white at the Map display's
# alpha 0.7 over the 48-grey background (0.7 x 255 + 0.3 x 48 = 192.9); its walls: black at
# 0.7 (0.3 x 48 = 14.4). The map covers the whole view: its free grey finds the view's bounds.
FLOOR_RGB255 = (192, 192, 192)
FLOOR_TOLERANCE = 6  # Mesa's blending rounds either way
MAP_COLOURS = {'floor plan (free)': (192 / 255,) * 3, 'floor plan (walls)': (14 / 255,) * 3}
MIN_MAP_PIXELS = 2000  # at 40 px/m the hall's walls in view are ~14000 px, its floor ~400000
# Each robot in its colour in the world file: its scan, its trail and its arrow. The four
# lasers see the same walls and rviz draws their points in no fixed order, so one scan may
# cover another on the screen: the scans are counted together (their points along the hall's
# walls: thousands of pixels; all the robots' arrows and trails: under 300), and each robot's
# colour must show (its arrow and trail once it has driven: 40-85 px, shaded by rviz's light).
# That rviz subscribes to every scan is asserted too.
ROBOT_COLOURS = {'robot_0 (blue)': (0.0, 0.0, 1.0), 'robot_1 (red)': (1.0, 0.0, 0.0),
                 'robot_2 (green)': (0.0, 1.0, 0.0), 'robot_3 (magenta)': (1.0, 0.0, 1.0)}
MIN_ROBOT_PIXELS = 20
MIN_SCAN_PIXELS = 1000
#: Topics a run of the lesson must leave in the bag for the view (and their types).
BAG_TOPICS = dict([('/map', 'nav_msgs/OccupancyGrid'), ('/clock', 'rosgraph_msgs/Clock'),
                   ('/tf', 'tf2_msgs/TFMessage'), ('/tf_static', 'tf2_msgs/TFMessage')]
                  + [('/robot_%d/base_scan' % i, 'sensor_msgs/LaserScan') for i in range(ROBOTS)]
                  + [('/robot_%d/base_pose_ground_truth' % i, 'nav_msgs/Odometry')
                     for i in range(ROBOTS)])


def missing_from_view(shot):
    """What the screenshot does not show of the lesson's view (empty once it all shows)."""
    view = render_area(shot, FLOOR_RGB255, FLOOR_TOLERANCE)
    if view.size == 0:
        return ["rviz's 3D view (no floor plan grey)"]
    colours = {**MAP_COLOURS, **ROBOT_COLOURS}
    # Each with its count: a failure says how far short it fell.
    missing = ['%s (%d px)' % (name, colour_pixels(view, colours[name]))
               for name in (missing_colours(view, MAP_COLOURS, MIN_MAP_PIXELS)
                            + missing_colours(view, ROBOT_COLOURS, MIN_ROBOT_PIXELS))]
    scans = sum(colour_pixels(view, rgb) for rgb in ROBOT_COLOURS.values())
    if scans < MIN_SCAN_PIXELS:
        missing.append('the scans (%d px of the robots\' colours, expected %d)'
                       % (scans, MIN_SCAN_PIXELS))
    return missing


def config_path():
    return os.path.join(rospkg.RosPack().get_path('multi_sync'), 'rviz', 'multi_sync.rviz')


class StageViewsTest(ScratchDirTestCase):
    TMP_PREFIX = 'test_stage_views_'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        rospy.init_node('test_stage_views')

    def wait_view(self, rviz, what):
        """Waits until rviz's screen shows the floor plan and every scan; returns the shot."""
        last = {'missing': None}

        def shown():
            shot = rviz.grab()
            last['missing'] = missing_from_view(shot)
            return [shot] if not last['missing'] else None
        try:
            return wait_for(lambda: rviz.alive_and(shown), RVIZ_DEADLINE_S, what,
                            poll_s=0.5)[0]
        except AssertionError as err:
            Image.fromarray(rviz.grab()).save(os.path.join(results_dir(), 'stage_rviz_failed.png'))
            raise AssertionError('%s; not shown: %s' % (err, last['missing'])) from None

    def assert_rviz_clean(self, rviz):
        self.assertEqual(rviz.missing_topics(), [])
        self.assertEqual(error_lines(rviz.log()), [], rviz.log())

    def test_live_run_in_rviz_then_its_bag_played_back(self):
        # One test: the playback needs the run it records.
        self.play_back(self.record_live_run())

    def record_live_run(self):
        """rviz on the lesson while rosbag records it and the monitor gives GO; the bag."""
        watch = StageWatch(ROBOTS)
        self.addCleanup(watch.close)
        rviz = RvizOnXvfb(config_path(), 'rviz_live')
        self.addCleanup(rviz.close)
        self.assertEqual(rviz.topics, sorted(BAG_TOPICS.keys() - {'/clock'}))
        rviz.wait_subscribed(RVIZ_DEADLINE_S)

        bag_path = self.path('stage_lesson.bag')
        recorder = ChildProcess(['rosrun', 'rosbag', 'record', '-a', '-O', bag_path,
                                 '__name:=' + RECORDER],
                                log_path=os.path.join(results_dir(), 'stage_rosbag_record.log'))
        self.addCleanup(recorder.stop)
        recorder.start()
        wait_for(lambda: all('/' + RECORDER in subscribers_of(t) for t in BAG_TOPICS),
                 START_DEADLINE_S, 'rosbag record subscribed to %s' % ', '.join(BAG_TOPICS),
                 alive=recorder.alive)

        monitor = NodeProcess('monitor', str(ROBOTS))
        self.addCleanup(monitor.stop)
        wait_for(watch.gos, START_DEADLINE_S, "the monitor's GO", alive=monitor.alive)
        wait_for(watch.moved, DRIVE_DEADLINE_S, 'every robot to move after GO')
        wait_for(lambda: all(watch.stopped(i) for i in watch.ids()), DRIVE_DEADLINE_S,
                 'every robot to stop (bumper or teammate)')

        shot = self.wait_view(rviz, 'rviz showing the floor plan and the four scans (live)')
        Image.fromarray(shot).save(os.path.join(results_dir(), 'stage_rviz_live.png'))
        self.assert_rviz_clean(rviz)

        self.assertEqual(recorder.stop(BAG_CLOSE_DEADLINE_S), 0, recorder.tail())
        with rosbag.Bag(bag_path) as bag:
            topics = bag.get_type_and_topic_info().topics
        for topic, msg_type in BAG_TOPICS.items():
            self.assertIn(topic, topics)
            self.assertEqual(topics[topic].msg_type, msg_type, topic)
            self.assertGreater(topics[topic].message_count, 0, topic)
        return bag_path

    def play_back(self, bag_path):
        """The bag into a fresh rviz on a fresh master with /use_sim_time: the view again."""
        # A master of this test's own: no Stage, no robots, only the bag. Roscore points this
        # process's ROS_MASTER_URI at it (rviz and the master queries follow); this node
        # stays on rostest's master.
        uri_before = os.environ['ROS_MASTER_URI']
        self.addCleanup(os.environ.__setitem__, 'ROS_MASTER_URI', uri_before)
        roscore = Roscore(log_path=os.path.join(results_dir(), 'stage_playback_roscore.log'))
        self.addCleanup(roscore.stop)
        roscore.start()
        rosgraph.Master('/test_stage_views', master_uri=roscore.uri).setParam('/use_sim_time',
                                                                               True)
        rviz = RvizOnXvfb(config_path(), 'rviz_playback')
        self.addCleanup(rviz.close)
        rviz.wait_subscribed(RVIZ_DEADLINE_S)

        player = ChildProcess(['rosrun', 'rosbag', 'play', bag_path],
                              log_path=os.path.join(results_dir(), 'stage_rosbag_play.log'))
        self.addCleanup(player.stop)
        player.start()
        self.assertEqual(player.wait_exit(PLAY_DEADLINE_S), 0, player.tail())
        # The whole run has been played: rviz keeps the last scans and the whole trails.
        shot = self.wait_view(rviz, 'rviz showing the floor plan and the four scans (bag)')
        Image.fromarray(shot).save(os.path.join(results_dir(), 'stage_rviz_playback.png'))
        self.assert_rviz_clean(rviz)


if __name__ == '__main__':
    rostest.rosrun('multi_sync', 'stage_views', StageViewsTest, sys.argv)
