"""Stage's worker-thread race, modelled deterministically (no rospy).

In Stage 4.3's World::Update the main thread wakes the worker threads (each consumes its
own event queue: the rangers, whose queue each drew with random() % threads + 1) and then
moves the robots one after another while they run; a ranger that starts before its robot's
move casts from the robot's pose before the step, one that starts after it from the new
pose. Which ones do is up to the operating system's scheduler.

Timed in the real Stage (a probe stamping every ranger update and every move: README, "How
close to Stage"): a ranger update costs about as much per beam whatever the world (1 to 3
us a beam), a move about two beams' worth per block of the robot's body (1.2 to 3 times a
beam: cave 3.5 us a block, hospital 4, pioneer_flocking 2.3), a robot standing still
nothing (ModelPosition::Move returns at once); the worker threads take their queues one
after another, in an order that changes from step to step, beside the main thread's moves.

The model, two virtual clocks counted in beams: the main thread's, through the moves in
move order (a moving robot's move costs MOVE_BEAMS_PER_BLOCK per block), and the workers',
through the queues one after another in an order drawn each step from the race's own
generator (seeded from the world's seed, never from random(): Stage's stream is the
controllers' and the noise's), each ranger costing its beams. A ranger casts from its
robot's pose before the move when the workers' clock reaches it before the main thread's
reaches its robot. (A ranger that starts during its robot's move reads, in Stage, the tried
pose or the kept one; here it casts after the move.) A world with one worker thread
(threads 0 or 1) keeps every cast after the moves, as Stage's single worker mostly has it
(the golden runs of simple, pioneer_walle and large agree with that to the bit until they
part from each other).
"""
import numpy as np

from .jit import kernel, njit

#: a move's cost per block of the robot's body, in beams (the real Stage's ratio, median of
#: cave, hospital, pioneer_flocking, SFU and fasr: 1.2, 2.2, 2.3, 3.0, 1.9)
MOVE_BEAMS_PER_BLOCK = 2.0
#: a constant mixed into the race generator's seed, so that its stream is its own
_STREAM = 0x5ace


def move_starts(move_order, move_cost):
    """Per robot, the main thread's clock when its move starts: the moves in `move_order`
    (robot indices), each costing move_cost[robot]."""
    start = np.empty(len(move_cost), np.float64)
    _move_starts(np.ascontiguousarray(move_order, np.int64),
                 np.ascontiguousarray(move_cost, np.float64), start)
    return start


def early_casts(queue_order, queue, cost, robot, move_start):
    """Per ranger (its queue, its cost, its robot; in update order within each queue),
    whether it starts before its robot's move: the workers take the queues in
    `queue_order` (queue numbers), one after another, from clock 0 (a queue not in it, with
    the first)."""
    arrays = [np.ascontiguousarray(a, t) for a, t in ((queue_order, np.int64), (queue, np.int64),
              (cost, np.float64), (robot, np.int64), (move_start, np.float64))]
    early = np.empty(len(arrays[1]), np.bool_)
    _early_casts(*arrays, early)
    return early


# Both clocks as a running sum, each start that sum less its own cost (numpy's cumsum less
# the cost, as the model was first written: the same floats, so the same casts).

@kernel
def _move_starts(move_order, move_cost, start):
    clock = 0.0
    for k in range(move_order.shape[0]):
        r = move_order[k]
        clock += move_cost[r]
        start[r] = clock - move_cost[r]


@njit(cache=True)
def _early_casts(queue_order, queue, cost, robot, move_start, early):
    most = queue_order.max()
    for k in range(queue.shape[0]):
        most = max(most, queue[k])
    turn = np.zeros(most + 1, np.int64)
    for t in range(queue_order.shape[0]):
        turn[queue_order[t]] = t
    clock = 0.0
    for t in range(queue_order.shape[0]):
        for k in range(queue.shape[0]):
            if turn[queue[k]] == t:
                clock += cost[k]
                early[k] = clock - cost[k] < move_start[robot[k]]


class WorkerRace:
    """A world's race: per step, which due rangers cast from their robot's earlier pose."""

    def __init__(self, threads, seed, slot_beams, slot_robot, robot_blocks, move_order):
        """slot_beams, slot_robot: per ranger slot, its beams and the robot carrying it;
        robot_blocks: per robot, its body's blocks; move_order: the robots in the order
        they move."""
        self.threads = int(threads)
        self._rng = np.random.default_rng([_STREAM, 1 if seed is None else int(seed)])
        self._beams = np.asarray(slot_beams, np.float64)
        self._robot = np.asarray(slot_robot, np.int64)
        self._block_cost = MOVE_BEAMS_PER_BLOCK * np.asarray(robot_blocks, np.float64)
        self._move_order = np.asarray(move_order, np.int64)

    @staticmethod
    def applies(threads):
        """Whether a world with `threads` worker threads races (more than one worker)."""
        return int(threads) > 1

    def stale(self, queue, slots, moving):
        """One step: per due ranger (its queue and ranger slot, in update order), whether it
        casts from its robot's pose before the move; moving: per robot, whether it moves."""
        queue_order = self._rng.permutation(self.threads) + 1
        starts = move_starts(self._move_order, np.where(moving, self._block_cost, 0.0))
        return early_casts(queue_order, np.asarray(queue, np.int64), self._beams[slots],
                           self._robot[slots], starts)
