"""Who updates when, and whose callbacks run in which order: Stage's subscriptions, event
queues and update callbacks (no rospy).

In Stage a model updates only while someone subscribes to it (stageros subscribes every
robot and its rangers; a controller the models it reads and drives). The first subscription
starts it: a thread-safe model (a ranger, a fiducial finder) draws its worker queue with
random() % threads + 1, others use queue 0, and its first update is queued one
update_interval later. Each step, World::Update takes queue 0's due models in the main
thread, the workers' beside the moves, then, in series, calls the update callbacks of every
model that updated, queue by queue in the order they updated, then the world's callbacks.
The workers' queues are taken here one after the other, 1 to threads: in Stage they race
each other, so any fixed order is one Stage could have given (which of their rangers cast
before the moves is race.py's model of that race).

Batches: a model whose only update callback has a `batch` attribute may have it called
together with the next models' of the same batch (World.step does so), through
batch.prepare(entries) (a plan for all the world's (function, argument, owner) entries of
that batch, or None: call them one by one) and batch.run(plan, rows), which calls the
entries `rows` (their places in `entries`, an int64 array) in turn; it must leave
everything as calling them in turn would (each with its argument, returning false) and
return how many it did: the one after those is then called on its own, and the rest after
it.
"""
from .events import EventQueue

CB_UPDATE, CB_FLAGINCR, CB_FLAGDECR, CB_STARTUP, CB_SHUTDOWN = (
    'update', 'flag_incr', 'flag_decr', 'startup', 'shutdown')
CALLBACK_KINDS = (CB_UPDATE, CB_FLAGINCR, CB_FLAGDECR, CB_STARTUP, CB_SHUTDOWN)


class Scheduler:
    """The world's subscriptions, event queues and callbacks."""

    def __init__(self, threads, random):
        self.threads = max(1, int(threads))
        self.random = random
        self.queues = [EventQueue() for _ in range(self.threads + 1)]
        self.subs = {}         # model -> subscription count
        self.queue_of = {}     # model -> its event queue, drawn at its start-up
        self.callbacks = {}    # (model, kind) -> [(function, argument, owner)]
        self.world_callbacks = []
        # the controller running now (its init or callback), which owns what it adds; and
        # what to do when an owned callback raises (it is then removed)
        self.owner = None
        self.on_error = None
        # told of each model's Startup and Shutdown (the energy model: energy.Energy)
        self.lifecycle = None
        # bumped at every change of subscriptions or update callbacks (the World keeps
        # arrays of both, remade when this changes)
        self.version = 0
        self._queued_in = {}   # model -> the queues it has a slot in

    # ---- subscriptions -------------------------------------------------------------------
    def subscribed(self, model):
        return self.subs.get(model, 0) > 0

    def subscribe(self, model, now_us):
        """Model::Subscribe: the first one starts the model (Model::Startup)."""
        count = self.subs.get(model, 0) + 1
        self.subs[model] = count
        if count == 1:
            queue = (self.random.random() % self.threads) + 1 if model.thread_safe else 0
            self.queue_of[model] = queue
            self.queues[queue].push(now_us + model.interval_us, model)
            self._queued_in.setdefault(model, set()).add(queue)
            self._requeue(model, model.interval_us)
            if self.lifecycle is not None:
                self.lifecycle.started(model)
            self.call(model, CB_STARTUP)

    def unsubscribe(self, model):
        """Model::Unsubscribe: the last one shuts the model down (its queued update still
        comes once, and is not queued again)."""
        count = self.subs.get(model, 0)
        if count <= 0:
            return False
        self.subs[model] = count - 1
        if count == 1:
            self._requeue(model, None)
            self.call(model, CB_SHUTDOWN)
            if self.lifecycle is not None:
                self.lifecycle.stopped(model)
            return True
        return False

    def _requeue(self, model, interval):
        """Every queue holding the model queues it again at `interval` (None: not again),
        as its subscription now says."""
        self.version += 1
        for queue in self._queued_in.get(model, ()):
            self.queues[queue].set_interval(model, interval)

    # ---- a step --------------------------------------------------------------------------
    def due(self, queue, now_us):
        """The models of one queue that update now, in Stage's order; each is queued again
        while subscribed."""
        q = self.queues[queue]
        return [q.items[s] for s in q.consume_slots(now_us).tolist()]

    def due_indices(self, queue, now_us):
        """due() as the models' indices (int64 array)."""
        q = self.queues[queue]
        return q.tags[q.consume_slots(now_us)]

    # ---- callbacks -----------------------------------------------------------------------
    def add_callback(self, model, kind, function, argument=None):
        if kind not in CALLBACK_KINDS:
            raise ValueError('unknown callback kind %r (one of %s)'
                             % (kind, ', '.join(CALLBACK_KINDS)))
        self.callbacks.setdefault((model, kind), []).append((function, argument, self.owner))
        self.version += 1

    def has_callbacks(self, model, kind):
        return bool(self.callbacks.get((model, kind)))

    def call(self, model, kind):
        """Model::CallCallbacks: each in the order added; one that returns true is removed."""
        entries = self.callbacks.get((model, kind))
        if entries:
            keep = [e for e in list(entries) if not self._run(e, model)]
            if len(keep) != len(entries):
                self.callbacks[(model, kind)] = keep
                self.version += 1

    def add_world_callback(self, function, argument=None):
        self.world_callbacks.append((function, argument, self.owner))

    def call_world(self, world):
        """The world's update callbacks; one that returns true is removed."""
        if self.world_callbacks:
            self.world_callbacks = [e for e in self.world_callbacks if not self._run(e, world)]

    def _run(self, entry, subject):
        """Calls one callback as its owner; True if it is done (returned true, or raised:
        then reported through on_error)."""
        function, argument, owner = entry
        previous, self.owner = self.owner, owner
        try:
            return bool(function(subject, argument))
        except Exception as err:
            if owner is None or self.on_error is None:
                raise
            self.on_error(owner, subject, err)
            return True
        finally:
            self.owner = previous
