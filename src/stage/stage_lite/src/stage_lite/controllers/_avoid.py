"""The beam rule Stage's wander, fasr and fasr2 share (examples/ctrl/wander.cc, fasr.cc,
fasr2.cc), each with its own middle part and distances: something nearer than `front` in the
middle beams, from n/part to n - n/part exclusive (integer division), is an obstruction;
anything nearer than `stop` anywhere stops the robot; the left half is i > n/2, the right
half the rest. And the avoid step fasr and fasr2 take on it (their ObstacleAvoid), in
Python and in their batches' kernels. Not a controller itself (no init)."""
import numpy as np

from stage_lite.model.glibc_random import random_next
from stage_lite.model.jit import kernel
from stage_lite.model.robot_state import MODE_CODE

VELOCITY = MODE_CODE['velocity']

AVOID_PART = 4        # fasr's and fasr2's avoid step reads the scan's middle half


def beam_rule(scan, part, front, stop):
    """(obstruction ahead, something too close, nearest on the left, nearest on the
    right) of a scan."""
    obstruction, too_close, min_left, min_right = _beam_rule(
        np.asarray(scan, np.float64), part, front, stop)
    return bool(obstruction), bool(too_close), min_left, min_right


def avoid_step(pos, scan, count, front, stop, speed, turn, duration):
    """fasr's and fasr2's ObstacleAvoid on a laser scan (middle half: part 4), with its avoid
    count: (True while avoiding, the count after this call). Something ahead, too close or
    a count left: creep at `speed` (stand if too close); a new avoid turns `turn` rad/s away
    from the nearer side for random() % duration + duration calls (the world's stream)."""
    obstruction, too_close, min_left, min_right = beam_rule(scan, AVOID_PART, front, stop)
    if not (obstruction or too_close or count > 0):
        return False, count
    pos.set_x_speed(0.0 if too_close else speed)
    if count < 1:
        count = pos.world.random() % duration + duration
        pos.set_turn_speed(-turn if min_left < min_right else turn)
    return True, count - 1


@kernel
def _beam_rule(scan, part, front, stop):
    n = scan.shape[0]
    obstruction = False
    too_close = False
    min_left = 1e6
    min_right = 1e6
    for i in range(n):
        r = scan[i]
        if i > n // part and i < n - n // part and r < front:
            obstruction = True
        if r < stop:
            too_close = True
        if i > n // 2:
            min_left = min(min_left, r)
        else:
            min_right = min(min_right, r)
    return obstruction, too_close, min_left, min_right


@kernel
def avoid_step_in_kernel(scan, avoid, i, command, mode, p, table, pointers, front, stop,
                         speed, turn, duration):
    """avoid_step for a batch's kernel: robot i's avoid count in avoid[i], its command in
    row p of command and mode, random()'s stream as (table, pointers) (random_next). True
    while avoiding."""
    obstruction, too_close, min_left, min_right = _beam_rule(scan, AVOID_PART, front, stop)
    if not (obstruction or too_close or avoid[i] > 0):
        return False
    command[p, 0] = 0.0 if too_close else speed
    mode[p] = VELOCITY
    if avoid[i] < 1:                          # a new avoid: its count drawn
        avoid[i] = random_next(table, pointers) % duration + duration
        command[p, 3] = -turn if min_left < min_right else turn
    avoid[i] -= 1
    return True


def laser_rows(pos, sensor, arrays):
    """Where a batch's kernel finds a robot: ((the world's beams, goals, modes, poses), where
    the sensor's ranges start in the beams, the robot's row in the others); None when those
    arrays are not `arrays` (the robots' before it; None for the first), or the robot's
    command and pose rows differ, or the world does not cast the sensor."""
    place = sensor.first_range_at()
    goal, mode, row = pos.command_rows()
    pose, pose_row = pos.pose_rows()
    if place is None or pose_row != row:
        return None
    here = (place[0], goal, mode, pose)
    if arrays is not None and any(a is not b for a, b in zip(here, arrays, strict=True)):
        return None
    return here, place[1], row
