"""The demos' command line (convoy_demo, stage_demo): --out, bounded options, main()'s exits.

Pure (no rospy). argparse reports a bad command line and exits 2; a demo's run returns its
exit code; Ctrl-C ends it with the shell's 130.
"""
import argparse
import os
import sys

INTERRUPTED_EXIT = 130  # 128 + SIGINT: what a shell reports for a program ended by Ctrl-C


def demo_parser(prog, description, out_help):
    """An ArgumentParser with the demos' --out DIR (required, made absolute)."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument('--out', required=True, type=os.path.abspath, help=out_help)
    return parser


def bounded(kind, low, high, unit=''):
    """An argparse type: the argument as kind (int or float), refused outside [low, high]."""
    def convert(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError('expected %s, got %r' % (
                'an integer' if kind is int else 'a number', text)) from None
        if not low <= value <= high:  # False for nan too
            raise argparse.ArgumentTypeError('must be between %g and %g%s, got %s'
                                             % (low, high, ' ' + unit if unit else '', text))
        return value
    return convert


def demo_main(prog, parse_args, run, argv=None):
    """A demo's main(): sys.exit(run(parse_args(argv))), 130 on Ctrl-C with 'PROG: interrupted'.

    argv: the arguments after the program name (default sys.argv[1:]).
    """
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        sys.exit(run(args))
    except KeyboardInterrupt:
        print('%s: interrupted' % prog, file=sys.stderr)
        sys.exit(INTERRUPTED_EXIT)
