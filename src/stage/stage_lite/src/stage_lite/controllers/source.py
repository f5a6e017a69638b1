"""Stage's `source` (examples/ctrl/source.cc): `ctrl "source N"` keeps up to N flags on the
model, one new yellow flag of 0.25 per update while it has fewer. Stage reads N with atoi
from the second word (more words are ignored); a missing or non-numeric N is an error here
(Stage's release build reads garbage or 0)."""
from stage_lite.model.stage_api import Flag

FLAG_COLOR = (1.0, 1.0, 0.0, 1.0)
FLAG_SIZE = 0.25


def init(model, args):
    words = args.words()
    if len(words) < 2:
        raise ValueError('source needs its capacity: ctrl "source N"')
    try:
        capacity = int(words[1])
    except ValueError:
        raise ValueError('source\'s capacity must be a whole number, got "%s"'
                         % words[1]) from None
    if capacity < 0:
        raise ValueError('source\'s capacity must be 0 or more, got %d' % capacity)
    model.add_callback('update', lambda m, _: _refill(m, capacity))
    model.subscribe()


def _refill(model, capacity):
    if model.get_flag_count() < capacity:
        model.push_flag(Flag(FLAG_COLOR, FLAG_SIZE))
    return False
