"""Unit tests for draw_square's state machine and goal maths (square_driver)."""

import math
import struct
from dataclasses import dataclass, replace

import pytest
from turtle_lite.square_driver import PI, SquareDriver, State

CENTRE = 5.5444446  # turtlesim's turtle1 start, float32
DT = 0.016
P = 3.14159265  # the simulator's normalisation literal (turtle.cpp)


def f32(value):
    return struct.unpack("f", struct.pack("f", value))[0]


@dataclass(frozen=True)
class FakePose:
    x: float = CENTRE
    y: float = CENTRE
    theta: float = 0.0
    linear_velocity: float = 0.0
    angular_velocity: float = 0.0


def run_square(ticks):
    """Close the loop with a minimal turtlesim tick (heading first, then position).

    Each tick the driver sees the last published pose and its command is applied on the
    simulator's next update, as with a 1-deep cmd_vel queue. Returns the logged events.
    """
    driver = SquareDriver()
    x, y, theta, vx, w = CENTRE, CENTRE, 0.0, 0.0, 0.0
    pose = FakePose()
    events = []
    for _ in range(ticks):
        step = driver.step(pose)
        if step.reached:
            events.append("Reached goal")
        if step.new_goal is not None:
            g = step.new_goal
            events.append("New goal [%f %f, %f]" % (g.x, g.y, g.theta))
        if step.command is not None:
            vx, w = step.command
        theta += w * DT
        theta -= 2 * P * math.floor((theta + P) / (2 * P))
        x += math.cos(theta) * vx * DT
        y += math.sin(theta) * vx * DT
        pose = FakePose(f32(x), f32(y), f32(theta), f32(abs(vx)), f32(w))
    return events


def test_first_goals_match_turtlesims_log():
    # the real draw_square logs these first three goals.
    # Printed with %f, so they agree to the last printed digit (tolerance 2e-6).
    goals = [e for e in run_square(800) if e.startswith("New goal")]
    expected = [(7.544445, 5.544445, 0.0), (7.448444, 5.544445, 1.570796),
                (7.466837, 7.544360, 1.561600)]
    got = [tuple(float(v) for v in g[len("New goal ["):-1].replace(",", "").split())
           for g in goals[:3]]
    for g, e in zip(got, expected, strict=True):
        assert g == pytest.approx(e, abs=2e-6)


def test_log_order_reached_then_new_goal():
    events = run_square(800)
    assert events[0].startswith("New goal")
    assert events[1] == "Reached goal"
    assert events[2].startswith("New goal")
    assert events.count("Reached goal") >= 3


def test_nothing_before_first_pose():
    driver = SquareDriver()
    step = driver.step(None)
    assert step.command is None and step.new_goal is None and not step.reached
    assert driver.goal is None


def test_first_pose_sets_goal_ahead_and_drives():
    step = SquareDriver().step(FakePose(theta=math.pi / 2))
    assert step.command == (1.0, 0.0)
    # 2 m ahead along +y; float32 goal (tolerance 1e-6).
    assert (step.new_goal.x, step.new_goal.y) == pytest.approx((CENTRE, CENTRE + 2.0), abs=1e-6)


@pytest.mark.parametrize(
    ("state", "pose", "command", "next_state"),
    [
        # Moving but not yet at rest: keep sending zero Twists.
        (State.STOP_FORWARD, FakePose(linear_velocity=1.0), (0.0, 0.0), State.STOP_FORWARD),
        (State.STOP_FORWARD, FakePose(angular_velocity=0.0002), (0.0, 0.0), State.STOP_FORWARD),
        (State.STOP_TURN, FakePose(angular_velocity=0.4), (0.0, 0.0), State.STOP_TURN),
        # At rest: no Twist this tick, next phase.
        (State.STOP_FORWARD, FakePose(), None, State.TURN),
        (State.STOP_TURN, FakePose(), None, State.FORWARD),
        # Below the 0.0001 threshold counts as rest.
        (State.STOP_TURN, FakePose(linear_velocity=0.00009), None, State.FORWARD),
    ],
)
def test_stop_states(state, pose, command, next_state):
    driver = SquareDriver()
    driver.step(FakePose())  # sets the first goal
    driver.state = state
    step = driver.step(pose)
    assert step.command == command
    assert driver.state is next_state
    assert step.reached is (command is None)


@pytest.mark.parametrize(
    ("theta", "goal_theta"),
    [
        (0.0, PI / 2),
        (1.5616, 1.5616 + PI / 2),
        # Past PI the goal wraps into [-PI, PI) with the truncated PI (1e-6 tolerance).
        (3.0, 3.0 + PI / 2 - 2 * PI),
        (-3.0, -3.0 + PI / 2),
        (PI / 2, -PI),
    ],
)
def test_turn_goal_wraps(theta, goal_theta):
    driver = SquareDriver()
    driver.step(FakePose(theta=theta))
    driver.state = State.STOP_FORWARD
    step = driver.step(FakePose(theta=theta))
    assert step.new_goal.theta == pytest.approx(goal_theta, abs=1e-6)
    assert -PI - 1e-6 <= step.new_goal.theta < PI


@pytest.mark.parametrize(
    ("offset", "reached"),
    [
        ({"x": 0.099}, True),
        ({"x": 0.101}, False),
        ({"y": -0.099}, True),
        ({"theta": 0.0099}, True),
        ({"theta": 0.0101}, False),
    ],
)
def test_goal_tolerance(offset, reached):
    driver = SquareDriver()
    driver.step(FakePose())
    g = driver.goal
    pose = replace(FakePose(), x=g.x, y=g.y, theta=g.theta)
    pose = replace(pose, **{k: getattr(pose, k) + v for k, v in offset.items()})
    step = driver.step(pose)
    assert (step.command == (0.0, 0.0)) is reached
    assert (driver.state is State.STOP_FORWARD) is reached


@pytest.mark.parametrize("field", ["x", "y", "theta", "linear_velocity", "angular_velocity"])
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_pose_raises(field, bad):
    with pytest.raises(ValueError, match=field):
        SquareDriver().step(replace(FakePose(), **{field: bad}))
