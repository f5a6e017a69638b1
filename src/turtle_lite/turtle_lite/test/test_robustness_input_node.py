#!/usr/bin/env python3
"""The simulator under bad input: NaN/inf, bad names, unknown kills, spawn/kill churn."""

import math
import threading

import rospy
import rostest
from course_common.testing import EVENT_DEADLINE_S, START_DEADLINE_S, wait_for
from course_common.testing.master import graph_names, published_topics
from course_common.testing.recorders import LogRecorder
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Log
from sim_support import SimTestCase, turtle_graph_names, wait_connected
from turtle_lite.testing import CENTER, PoseRecorder
from turtlesim.srv import Kill, Spawn, TeleportAbsolute, TeleportRelative

POSE_TOL = 1e-4
BAD_NUMBERS = (math.nan, math.inf, -math.inf)
TICKS_AFTER_BAD_INPUT = 30  # poses to watch after the last bad command (about 0.5 s)
CHURN = 50  # spawns in a row
THREADS = 4  # concurrent spawn/kill clients
PER_THREAD = 10


def turtles_on_master():
    """Turtle names whose pose topic is published."""
    return {t.split("/")[1] for t in published_topics() if t.endswith("/pose")}


class RobustnessInputTest(SimTestCase):
    RECORD_TURTLE1 = False  # each test records turtle1's poses afresh, in setUp

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.logs = LogRecorder("/turtlesim")

    def setUp(self):
        self.pose = PoseRecorder("/turtle1/pose")
        self.addCleanup(self.pose.close)
        self.pose.wait_latest(lambda p: True, "a first pose", START_DEADLINE_S)

    def assert_poses_finite(self, poses):
        for p in poses:
            values = (p.x, p.y, p.theta, p.linear_velocity, p.angular_velocity)
            self.assertTrue(all(math.isfinite(v) for v in values), f"non-finite pose {p}")

    def wait_more_poses(self, n, what):
        target = self.pose.count() + n
        wait_for(lambda: self.pose.count() >= target, EVENT_DEADLINE_S, what)

    def test_non_finite_cmd_vel_never_reaches_a_pose(self):
        self.pose.wait_latest(lambda p: p.linear_velocity == 0 and p.angular_velocity == 0,
                              "turtle1 at rest")
        before = self.pose.latest()
        pub = rospy.Publisher("/turtle1/cmd_vel", Twist, queue_size=10)
        self.addCleanup(pub.unregister)
        wait_connected(pub, "the simulator to subscribe /turtle1/cmd_vel")
        self.pose.clear()
        rate = rospy.Rate(50)
        for bad in BAD_NUMBERS:
            for field in ("linear.x", "linear.y", "angular.z"):
                twist = Twist()
                twist.linear.x = 1.0  # a good value beside the bad one
                obj, attr = field.split(".")
                setattr(getattr(twist, obj), attr, bad)
                pub.publish(twist)
                rate.sleep()
        self.wait_more_poses(TICKS_AFTER_BAD_INPUT, "poses after the bad commands")
        poses = self.pose.messages()
        self.assert_poses_finite(poses)
        self.assertAlmostEqual(poses[-1].x, before.x, delta=POSE_TOL)
        self.logs.wait_log("Ignoring cmd_vel")
        # Still alive and listening: a good command moves the turtle.
        good = Twist()
        good.angular.z = 0.5
        pub.publish(good)
        self.pose.wait_latest(lambda p: p.angular_velocity == 0.5, "the good command applied")

    def test_non_finite_teleports_fail_and_never_reach_a_pose(self):
        absolute = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
        relative = rospy.ServiceProxy("/turtle1/teleport_relative", TeleportRelative)
        self.pose.clear()
        for bad in BAD_NUMBERS:
            for args in ((bad, 1.0, 0.0), (1.0, bad, 0.0), (1.0, 1.0, bad)):
                with self.assertRaises(rospy.ServiceException, msg=f"absolute{args}"):
                    absolute(*args)
            for args in ((bad, 0.0), (0.0, bad)):
                with self.assertRaises(rospy.ServiceException, msg=f"relative{args}"):
                    relative(*args)
            with self.assertRaises(rospy.ServiceException):
                self.spawn(bad, 1.0, 0.0, "")
        self.wait_more_poses(TICKS_AFTER_BAD_INPUT, "poses after the bad teleports")
        self.assert_poses_finite(self.pose.messages())
        self.assertEqual(turtles_on_master(), {"turtle1"}, "a bad spawn created a turtle")
        # The services still work with good numbers.
        absolute(3.0, 4.0, 0.5)
        self.pose.wait_latest(lambda p: abs(p.x - 3.0) < POSE_TOL and abs(p.y - 4.0) < POSE_TOL,
                              "the good teleport")

    def test_bad_spawn_and_kill_names_fail_cleanly(self):
        for name, log in (("turtle1", "A turtled named [turtle1] already exists"),
                          ("my turtle", "Character [ ] at element [2] is not valid"),
                          ("1abc", "Character [1] is not valid as the first character")):
            with self.assertRaises(rospy.ServiceException, msg=name):
                self.spawn(1.0, 1.0, 0.0, name)
            self.assertEqual(self.logs.wait_log(log).level, Log.ERROR)
        for name in ("nobody", "", "/turtle1"):
            with self.assertRaises(rospy.ServiceException, msg=name):
                self.kill(name)
            self.logs.wait_log(f"Tried to kill turtle [{name}], which does not exist")
        self.assertEqual(turtles_on_master(), {"turtle1"})
        self.wait_more_poses(5, "turtle1 still publishing")

    def test_kill_and_reset_unregister_from_the_master(self):
        names = [self.spawn(2.0, 2.0, 0.0, n).name for n in ("tk_a", "tk_b")]
        for name in names:
            topics, services = turtle_graph_names(f"/{name}")
            wait_for(lambda t=topics, s=services: t <= graph_names()[0] and s <= graph_names()[1],
                     EVENT_DEADLINE_S, f"the resources of {name} on the master")
        self.kill("tk_a")
        topics, services = turtle_graph_names("/tk_a")
        wait_for(lambda: not (topics & graph_names()[0]) and not (services & graph_names()[1]),
                 EVENT_DEADLINE_S, "tk_a's topics and services to leave the master")
        self.reset()
        topics, services = turtle_graph_names("/tk_b")
        wait_for(lambda: not (topics & graph_names()[0]) and not (services & graph_names()[1]),
                 EVENT_DEADLINE_S, "reset to remove tk_b's topics and services")
        self.assertEqual(turtles_on_master(), {"turtle1"})
        self.pose.wait_latest(lambda p: abs(p.x - CENTER) < POSE_TOL and p.theta == 0,
                              "turtle1 back at the centre after reset")
        self.assertEqual(self.spawn(1.0, 1.0, 0.0, "").name, "turtle2")
        self.kill("turtle2")

    def test_spawn_kill_churn_leaves_a_consistent_set(self):
        # 50 spawns in a row, killing every other one as we go.
        alive = {}
        previous = None
        for i in range(CHURN):
            x, y = 1.0 + (i % 10) * 0.9, 1.0 + (i // 10) * 1.5
            name = self.spawn(x, y, 0.0, "").name
            self.assertNotIn(name, alive)
            alive[name] = (x, y)
            if i % 2 == 1:
                self.kill(previous)
                del alive[previous]
            previous = name
        # Concurrent clients, each spawning and killing its own turtles.
        errors = []

        def client(k):
            try:
                spawn = rospy.ServiceProxy("/spawn", Spawn)
                kill = rospy.ServiceProxy("/kill", Kill)
                for j in range(PER_THREAD):
                    kill(spawn(5.0, 5.0, 0.0, f"cc{k}_{j}").name)
            except Exception as err:
                errors.append(repr(err))

        threads = [threading.Thread(target=client, args=(k,)) for k in range(THREADS)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(EVENT_DEADLINE_S * 4)
        self.assertEqual(errors, [])
        expected = set(alive) | {"turtle1"}
        wait_for(lambda: turtles_on_master() == expected, EVENT_DEADLINE_S,
                 f"exactly {len(expected)} turtles on the master")
        # Every survivor still publishes its own pose, where it was spawned.
        watchers = {n: PoseRecorder(f"/{n}/pose", keep=5) for n in alive}
        try:
            for name, (x, y) in alive.items():
                pose = watchers[name].wait_latest(lambda p: True, f"a pose from {name}")
                self.assertAlmostEqual(pose.x, x, delta=POSE_TOL, msg=name)
                self.assertAlmostEqual(pose.y, y, delta=POSE_TOL, msg=name)
        finally:
            for w in watchers.values():
                w.close()
        for name in alive:
            self.kill(name)
        wait_for(lambda: turtles_on_master() == {"turtle1"}, EVENT_DEADLINE_S,
                 "only turtle1 left")
        self.wait_more_poses(5, "turtle1 still publishing")


if __name__ == "__main__":
    rospy.init_node("test_robustness_input")
    rostest.rosrun("turtle_lite", "robustness_input", RobustnessInputTest)
