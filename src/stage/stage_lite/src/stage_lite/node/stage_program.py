"""Stage's own program, `stage [-g] [-c] [-a ARGS] WORLD`, as Stage 4.3.0's main.cc runs it:
the world and its controllers, no ROS (no master, no topics).

- `-g` (`--gui`): no window; the world steps as fast as it can (World::Run's loop), from
  the start: Stage's World reads no `paused` without its window;
- without `-g`: Stage's window (the one stageros has), stepping at the world's `speedup`,
  started paused when the world file says `paused 1`; closing it ends the program;
- `-c` (`--clock`): the clock line `[Stage:  0m 01s 000msec]` every show_clock_interval
  steps (the world's, default 100), rewritten in place with `\\r` as Stage does;
- `-a ARGS` (`--args ARGS`): the argument string every controller gets (CtrlArgs.cmdline);
- the world's `quit_time`: the program ends there (`[Stage: done]`, exit 0);
- Ctrl-C: the program ends at once, without a traceback (exit 130, as a shell reports a
  program that SIGINT ended).
A world that does not load: one `[FATAL]` line naming the file and line, exit 1; wrong
arguments: the usage, exit 2.
"""
import argparse
import os
import signal
import sys
import threading
import time

VERSION = 'Stage 4.3.0 (stage_lite)'
USAGE = 'stage [-g] [-c] [-a ARGS] WORLD'
EXIT_INTERRUPTED = 130


class ProgramArgs(argparse.ArgumentParser):
    def error(self, message):
        sys.stderr.write('stage: %s\nusage: %s\n' % (message, USAGE))
        sys.exit(2)


def parse_args(argv):
    parser = ProgramArgs(prog='stage', usage=USAGE, description='Stage 4.3 without ROS.')
    parser.add_argument('-g', '--gui', dest='headless', action='store_true',
                        help='run without a window (Stage\'s own wording: "--gui")')
    parser.add_argument('-c', '--clock', action='store_true',
                        help='print the simulation time periodically')
    parser.add_argument('-a', '--args', dest='ctrlargs', default='',
                        help='an argument string passed to all controllers')
    parser.add_argument('world', help='the world file')
    return parser.parse_args(argv)


def clock_line(sim_time_us):
    """World::ClockString: ` 0m 01s 000msec`, with hours first when there are some."""
    hours, rest = divmod(sim_time_us, 3600000000)
    minutes, rest = divmod(rest, 60000000)
    seconds, rest = divmod(rest, 1000000)
    text = '%dh' % hours if hours else ''
    return text + ' %dm %02ds %03dmsec' % (minutes, seconds, rest // 1000)


class Program:
    """One world stepped as `stage` steps it; `out` is where Stage prints."""

    def __init__(self, world, show_clock, out=sys.stdout):
        self.world = world
        self.show_clock = show_clock
        self.out = out

    def past_quit_time(self):
        q = self.world.quit_time_s
        return q > 0 and self.world.sim_time_us >= round(q * 1e6)

    def update(self):
        """World::Update: False once past quit_time (nothing done then)."""
        w = self.world
        if self.past_quit_time():
            return False
        if self.show_clock and w.updates % w.show_clock_interval == 0:
            self.out.write('\r[Stage: %s]' % clock_line(w.sim_time_us))
            self.out.flush()
        w.step()
        return True

    def run_headless(self, stop=None):
        """World::Run without a window: step until quit_time (or stop is set)."""
        while (stop is None or not stop.is_set()) and self.update():
            pass


def by_ctrl_c(err):
    """Whether err is Ctrl-C's KeyboardInterrupt, or an error it caused: numba boxes the
    arrays a kernel returns with a call back into Python, where the interrupt may surface,
    and the kernel's call then fails with a SystemError whose cause it is."""
    while err is not None:
        if isinstance(err, KeyboardInterrupt):
            return True
        err = err.__cause__
    return False


def load(args, out):
    """The world and its controllers, or one FATAL line on a line of its own and exit 1."""
    from ..model.world import WorldError, load_world
    try:
        return load_world(args.world, stageros=False, ctrlargs=args.ctrlargs)
    except WorldError as err:
        why = str(err)
    except Exception as err:  # an odd file: one line, never a traceback
        why = '%s: could not load the world: %s' % (args.world, err)
    out.write('\n')
    out.flush()
    sys.stderr.write('[FATAL] %s\n' % why)
    sys.exit(1)


def run_window(program):
    """Stage's window at the world's speedup; False if no window could be opened."""
    import rospy  # the window's own logging and shutdown flag; no master is used

    from ..view.gui import run_window as show
    from ..view.status import RateMeter, clock_string
    from ..view.world_view import WorldView
    from .step_loop import StepLoop

    world = program.world
    lock = threading.Lock()
    view = WorldView(world)
    rate = RateMeter()

    def step():
        with lock:
            if not program.update():
                rospy.signal_shutdown('quit_time')   # the window closes: Stage is done
                return None
            view.record()
            rate.add(time.monotonic(), world.sim_time_us / 1e6)
            return world.sim_time_us / 1e6

    def snapshot():
        with lock:
            return (world.updates, view.robots(),
                    clock_string(world.sim_time_us * 1000, rate.factor(), loop.paused))

    loop = StepLoop(step, world.interval_sim_s, world.speedup if world.speedup > 0 else -1)
    loop.pause(world.paused)
    signal.signal(signal.SIGINT, lambda *_: rospy.signal_shutdown('Ctrl-C'))
    loop.start()
    try:
        return show(world, view, snapshot, loop, lambda: world.updates)
    finally:
        loop.stop()
        loop.join(1.0)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    if not os.path.isfile(args.world):
        sys.stderr.write('[FATAL] %s: the world file does not exist\n' % args.world)
        sys.exit(1)
    out = sys.stdout
    out.write('%s %s%s\n' % (VERSION, '[Clock enabled]' if args.clock else '',
                             '[GUI disabled]' if args.headless else ''))
    out.write(' [Loading %s]' % args.world)
    out.flush()
    world = load(args, out)
    for line in world.warnings:
        sys.stderr.write('[WARN] %s\n' % line)
    if world.threads > 1:
        out.write('[threads %d]' % world.threads)
    out.write('\n')
    program = Program(world, args.clock, out)
    try:
        if args.headless or not run_window(program):
            program.run_headless()
    except (KeyboardInterrupt, SystemError) as err:
        if not by_ctrl_c(err):
            raise
        out.write('\n[Stage: interrupted]\n')
        out.flush()
        sys.exit(EXIT_INTERRUPTED)
    out.write('\n[Stage: done]\n')
    out.flush()
