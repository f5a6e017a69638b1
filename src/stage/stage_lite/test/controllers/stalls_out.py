"""A controller of the tests' own, in Python, found on STAGEPATH: drives its robot forward at
0.1 m/s from its first update, and raises once the sim time passes its argument (s)."""


def init(model, args):
    limit_us = float(args.words()[1]) * 1e6
    model.add_callback('update', drive, limit_us)
    model.subscribe()


def drive(model, limit_us):
    model.set_speed(0.1, 0.0, 0.0)
    if model.world.sim_time_now() > limit_us:
        raise RuntimeError('past my time')
    return False
