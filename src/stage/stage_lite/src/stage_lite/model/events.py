"""Stage's event queues: when each subscribed model updates, and in which order (no rospy).

Stage keeps one queue per thread (World::event_queues: queue 0 is the main thread's, queues
1..threads the workers'), each a std::priority_queue of (time, model) ordered by time alone.
Models updating at the same time come out in the order the heap leaves them, which is
libstdc++'s binary heap: push_heap sifts up, pop_heap moves the last element to the root and
sifts the hole down to a leaf before sifting the value up. That order decides whose
controller draws which random number and in what order the update callbacks run, so the heap
here does exactly what libstdc++'s does.

The heap holds (time, slot) pairs in two int64 arrays, a slot naming an item (the queue's
`items`, each with the interval it is queued again at, `interval`), so that a step's
consume runs in a numba kernel.
"""
import numpy as np

from .jit import kernel

#: an item's interval when it is not queued again (an unsubscribed model)
DROP = -1


class EventQueue:
    """A std::priority_queue of (time, item) under libstdc++: top() is an earliest event;
    among equal times, the one libstdc++'s heap would give. Items are hashable; each gets a
    slot the first time it is pushed (items[slot]) and an interval (interval[slot], DROP
    unless set_interval says otherwise) for consume_slots."""

    __slots__ = ('_times', '_slots', '_n', 'items', 'interval', 'tags', '_slot_of')

    def __init__(self):
        self._times = np.zeros(16, np.int64)
        self._slots = np.zeros(16, np.int64)
        self._n = 0
        self.items = []
        self.interval = np.full(16, DROP, np.int64)
        self.tags = np.full(16, -1, np.int64)     # per slot: the item's `index`, or -1
        self._slot_of = {}

    def __len__(self):
        return self._n

    def slot(self, item):
        """The item's slot (given at its first push, or now)."""
        s = self._slot_of.get(item)
        if s is None:
            s = self._slot_of[item] = len(self.items)
            self.items.append(item)
            if s >= self.interval.shape[0]:
                self.interval = _grown(self.interval, DROP)
                self.tags = _grown(self.tags, -1)
            index = getattr(item, 'index', -1)
            self.tags[s] = index if isinstance(index, int) else -1
        return s

    def set_interval(self, item, interval):
        """The interval the item is queued again at when consume_slots takes it (None: not
        queued again)."""
        self.interval[self.slot(item)] = DROP if interval is None else interval

    def push(self, time, item):
        s = self.slot(item)
        if self._n == self._times.shape[0]:
            self._times = _grown(self._times, 0)
            self._slots = _grown(self._slots, 0)
        _push(self._times, self._slots, self._n, time, s)
        self._n += 1
        return s

    def top_time(self):
        return int(self._times[0])

    def pop(self):
        """The top event, removed: (time, item)."""
        if not self._n:
            raise IndexError('pop from an empty event queue')
        time, s = int(self._times[0]), int(self._slots[0])
        self._n -= 1
        if self._n:
            _adjust(self._times, self._slots, 0, self._n, self._times[self._n],
                    self._slots[self._n])
        return time, self.items[s]

    def consume(self, now, interval_of):
        """World::ConsumeQueue: every item due at or before `now`, in the order Stage takes
        them; each is queued again at now + interval_of(item) as it is taken (Model::Update
        enqueues its next update before the next one is taken), or dropped where
        interval_of gives None (an unsubscribed model). Returns the items in order.
        interval_of is asked once per item due (the items due are known before the first is
        taken: those queued at or before now)."""
        n = self._n
        due = np.unique(self._slots[:n][self._times[:n] <= now])
        saved = self.interval[due].copy()
        for s in due.tolist():
            iv = interval_of(self.items[s])
            self.interval[s] = DROP if iv is None else iv
        order = self.consume_slots(now)
        self.interval[due] = saved
        return [self.items[s] for s in order.tolist()]

    def consume_slots(self, now):
        """consume() with each slot's own interval: the slots taken, in order (int64)."""
        out = np.empty(self._n, np.int64)
        taken, self._n = _consume(self._times, self._slots, self._n, now, self.interval, out)
        return out[:taken]


def _grown(a, fill):
    out = np.full(2 * a.shape[0], fill, a.dtype)
    out[:a.shape[0]] = a
    return out


# libstdc++'s __push_heap: `less(parent, value)` is parent.time > value.time
@kernel
def _sift_up(times, slots, hole, top, time, slot):
    parent = (hole - 1) // 2
    while hole > top and times[parent] > time:
        times[hole] = times[parent]
        slots[hole] = slots[parent]
        hole = parent
        parent = (hole - 1) // 2
    times[hole] = time
    slots[hole] = slot


@kernel
def _push(times, slots, n, time, slot):
    _sift_up(times, slots, n, 0, time, slot)


# libstdc++'s __adjust_heap: the hole at the root walks down to a leaf, by the child that
# is not less (the earlier time; the right one on a tie), then the value sifts up
@kernel
def _adjust(times, slots, hole, length, time, slot):
    top = hole
    child = hole
    while child < (length - 1) // 2:
        child = 2 * (child + 1)
        if times[child] > times[child - 1]:
            child -= 1
        times[hole] = times[child]
        slots[hole] = slots[child]
        hole = child
    if length % 2 == 0 and child == (length - 2) // 2:
        child = 2 * (child + 1)
        times[hole] = times[child - 1]
        slots[hole] = slots[child - 1]
        hole = child - 1
    _sift_up(times, slots, hole, top, time, slot)


@kernel
def _consume(times, slots, n, now, interval, out):
    """Pops every event due at or before now into out (slots, in order), pushing each again
    at now + interval[slot] unless that is DROP; returns (how many, the heap's new size).
    The heap's arrays have room: each pop frees the place its push takes."""
    taken = 0
    while n > 0 and times[0] <= now:
        s = slots[0]
        n -= 1
        if n > 0:
            _adjust(times, slots, 0, n, times[n], slots[n])
        out[taken] = s
        taken += 1
        iv = interval[s]
        if iv != DROP:
            _push(times, slots, n, now + iv, s)
            n += 1
    return taken, n
