"""Stage's `wander_accel` (examples/ctrl/wander_accel.cc): despite its name, wander's rule
with velocity commands (SetXSpeed, SetTurnSpeed; no acceleration), on the ranger its model
names `ranger:1` whatever its samples (wander looks for the first of ranger:0..15 with more
than 8). Stage 4.3.0 ships its source but does not build it: it calls ModelRanger::GetRanges,
which 4.3 no longer has; read as GetSensors()[0].ranges (what the scratch build of the real
plugin does)."""
from .wander import Wanderer

LASER = 'ranger:1'


def init(model, args):
    if len(args.words()) > 1:
        raise ValueError('wander_accel takes no arguments (Stage\'s ignores them), got "%s"'
                         % args.worldfile)
    if model.type != 'position':
        raise TypeError('wander_accel drives a position model, not a %s (Stage casts it'
                        ' unchecked)' % model.type)
    model.subscribe()
    laser = model.get_child(LASER)
    if laser is None or laser.type != 'ranger' or not laser.sensors:
        raise LookupError('%s has no %s.%s with a sensor (Stage dereferences it unchecked)'
                          % (model.token, model.token, LASER))
    wanderer = Wanderer(model, laser)
    laser.add_callback('update', wanderer.laser_update)
    laser.subscribe()
