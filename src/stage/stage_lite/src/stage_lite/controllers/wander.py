"""Stage's `wander` (examples/ctrl/wander.cc): cruise at 0.4 m/s; when the laser sees
something within 1 m in the middle third of its beams, or anything within 0.3 m, creep (or
stop) and turn away from the nearer side for 10 to 19 updates.

The decision is Stage's, beam for beam: the middle third is beams n/3 < i < n - n/3 (integer
division), the left half i > n/2, the right half the rest; the turn lasts random() % 10 + 10
updates, drawn from the world's random() stream when an avoidance starts.
"""
from ._avoid import beam_rule

CRUISE_SPEED = 0.4        # m/s
AVOID_SPEED = 0.05        # m/s, while turning away
AVOID_TURN = 0.5          # rad/s
MIN_FRONT_DISTANCE = 1.0  # m: an obstruction ahead
STOP_DISTANCE = 0.3       # m: anything this close stops it
AVOID_DURATION = 10       # updates, at least
MIN_SAMPLES = 9           # a laser has more than 8 samples
RANGERS_TRIED = 16        # ranger:0 ... ranger:15


def init(model, args):
    if model.type != 'position':
        raise TypeError('wander drives a position model, not a %s' % model.type)
    model.subscribe()
    laser = find_laser(model)
    if laser is None:
        raise LookupError('%s has no ranger with more than 8 samples (%s.ranger:0 to :%d)'
                          % (model.token, model.token, RANGERS_TRIED - 1))
    wanderer = Wanderer(model, laser)
    laser.add_callback('update', wanderer.laser_update)
    laser.subscribe()


def find_laser(model):
    """The first of the model's children ranger:0 ... ranger:15 whose first sensor has more
    than 8 samples, or None."""
    for i in range(RANGERS_TRIED):
        child = model.get_child('ranger:%d' % i)
        if child is not None and child.type == 'ranger' and child.sensors \
                and child.sensors[0].sample_count >= MIN_SAMPLES:
            return child
    return None


def decide(scan):
    """(obstruction ahead, something too close, nearest on the left, nearest on the right)
    of a scan, by wander's beam rule: its middle third, 1 m ahead, 0.3 m anywhere."""
    return beam_rule(scan, 3, MIN_FRONT_DISTANCE, STOP_DISTANCE)


class Wanderer:
    """One robot's wander state: how many more updates it keeps turning away."""

    def __init__(self, position, laser):
        self.position = position
        self.laser = laser
        self.avoid_count = 0

    def laser_update(self, laser, _):
        scan = self.laser.sensors[0].ranges
        if len(scan) < 1:
            return False
        obstruction, stop, min_left, min_right = decide(scan)
        pos = self.position
        if obstruction or stop or self.avoid_count > 0:
            pos.set_x_speed(0.0 if stop else AVOID_SPEED)
            if self.avoid_count < 1:       # a new avoidance: its length and side, kept
                self.avoid_count = pos.world.random() % AVOID_DURATION + AVOID_DURATION
                pos.set_turn_speed(-AVOID_TURN if min_left < min_right else AVOID_TURN)
            self.avoid_count -= 1
        else:
            self.avoid_count = 0
            pos.set_x_speed(CRUISE_SPEED)
            pos.set_turn_speed(0.0)
        return False
