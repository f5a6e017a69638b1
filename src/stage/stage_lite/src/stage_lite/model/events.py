"""Stage's event queues: when each subscribed model updates, and in which order (no rospy).

Stage keeps one queue per thread (World::event_queues: queue 0 is the main thread's, queues
1..threads the workers'), each a std::priority_queue of (time, model) ordered by time alone.
Models updating at the same time come out in the order the heap leaves them, which is
libstdc++'s binary heap: push_heap sifts up, pop_heap moves the last element to the root and
sifts the hole down to a leaf before sifting the value up. That order decides whose
controller draws which random number and in what order the update callbacks run, so the heap
here does exactly what libstdc++'s does.
"""


class EventQueue:
    """A std::priority_queue of (time, item) under libstdc++: top() is an earliest event;
    among equal times, the one libstdc++'s heap would give."""

    __slots__ = ('_times', '_items')

    def __init__(self):
        self._times = []
        self._items = []

    def __len__(self):
        return len(self._times)

    def push(self, time, item):
        self._times.append(time)
        self._items.append(item)
        self._sift_up(len(self._times) - 1, 0, time, item)

    def top_time(self):
        return self._times[0]

    def pop(self):
        """The top event, removed: (time, item)."""
        times, items = self._times, self._items
        top = (times[0], items[0])
        last_time, last_item = times.pop(), items.pop()
        if times:
            self._adjust(0, len(times), last_time, last_item)
        return top

    def consume(self, now, interval_of):
        """World::ConsumeQueue: every item due at or before `now`, in the order Stage takes
        them; each is queued again at now + interval_of(item) as it is taken (Model::Update
        enqueues its next update before the next one is taken), or dropped where
        interval_of gives None (an unsubscribed model). Returns the items in order."""
        out = []
        times = self._times
        while times and times[0] <= now:
            _, item = self.pop()
            out.append(item)
            interval = interval_of(item)
            if interval is not None:
                self.push(now + interval, item)
        return out

    # libstdc++'s __push_heap: `less(parent, value)` is parent.time > value.time
    def _sift_up(self, hole, top, time, item):
        times, items = self._times, self._items
        parent = (hole - 1) // 2
        while hole > top and times[parent] > time:
            times[hole] = times[parent]
            items[hole] = items[parent]
            hole = parent
            parent = (hole - 1) // 2
        times[hole] = time
        items[hole] = item

    # libstdc++'s __adjust_heap: the hole at the root walks down to a leaf, by the child that
    # is not less (the earlier time; the right one on a tie), then the value sifts up
    def _adjust(self, hole, length, time, item):
        times, items = self._times, self._items
        top = hole
        child = hole
        while child < (length - 1) // 2:
            child = 2 * (child + 1)
            if times[child] > times[child - 1]:
                child -= 1
            times[hole] = times[child]
            items[hole] = items[child]
            hole = child
        if length % 2 == 0 and child == (length - 2) // 2:
            child = 2 * (child + 1)
            times[hole] = times[child - 1]
            items[hole] = items[child - 1]
            hole = child - 1
        self._sift_up(hole, top, time, item)
