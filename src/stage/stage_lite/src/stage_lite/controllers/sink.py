"""Stage's `sink` (examples/ctrl/sink.cc): counts the flags delivered to it. One count for
every sink of the process, as the plugin's global counter is."""

delivered = 0


def init(model, args):
    model.add_callback('flag_incr', _delivery)
    model.subscribe()


def _delivery(model, _):
    global delivered
    delivered += 1
    return False
