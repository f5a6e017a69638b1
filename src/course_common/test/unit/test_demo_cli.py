"""Unit tests of course_common.demo_cli: the demos' --out, bounded options and exit codes."""
import os
import signal

import pytest
from course_common.demo_cli import INTERRUPTED_EXIT, bounded, demo_main, demo_parser


def _parser():
    parser = demo_parser('demo', 'a demo', 'where it writes')
    parser.add_argument('--n', type=bounded(int, 2, 10), default=3)
    parser.add_argument('--speed', type=bounded(float, 0.05, 1.0, 'm/s'), default=0.2)
    return parser


def test_out_is_made_absolute_and_defaults_hold(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    args = _parser().parse_args(['--out', 'pictures'])
    assert (args.out, args.n, args.speed) == (os.path.join(str(tmp_path), 'pictures'), 3, 0.2)


@pytest.mark.parametrize('argv, n, speed', [
    (['--n', '2', '--speed', '0.05'], 2, 0.05),   # the bounds are allowed
    (['--n', '10', '--speed', '1'], 10, 1.0),
])
def test_bounds_are_inclusive(argv, n, speed):
    args = _parser().parse_args(['--out', '/tmp/x', *argv])
    assert (args.n, args.speed) == (n, pytest.approx(speed, abs=0.0))
    assert type(args.n) is int and type(args.speed) is float


@pytest.mark.parametrize('argv, message', [
    ([], 'the following arguments are required: --out'),
    (['--out', 'x', '--n', '1'], 'argument --n: must be between 2 and 10, got 1'),
    (['--out', 'x', '--n', '11'], 'argument --n: must be between 2 and 10, got 11'),
    (['--out', 'x', '--n', '2.5'], "argument --n: expected an integer, got '2.5'"),
    (['--out', 'x', '--speed', '2'], 'argument --speed: must be between 0.05 and 1 m/s, got 2'),
    (['--out', 'x', '--speed', 'nan'], 'argument --speed: must be between 0.05 and 1 m/s, got nan'),
    (['--out', 'x', '--speed', 'fast'], "argument --speed: expected a number, got 'fast'"),
])
def test_bad_command_lines_exit_2_with_the_reason(capsys, argv, message):
    with pytest.raises(SystemExit) as end:
        _parser().parse_args(argv)
    assert end.value.code == 2
    assert message in capsys.readouterr().err


def _interrupted(_args):
    raise KeyboardInterrupt


@pytest.mark.parametrize('outcome, code, err', [
    (lambda _args: 0, 0, ''),
    (lambda _args: 1, 1, ''),
    (_interrupted, INTERRUPTED_EXIT, 'demo: interrupted\n'),
])
def test_demo_main_exits_with_the_runs_code(capsys, outcome, code, err):
    seen = []

    def run(args):
        seen.append(args)
        return outcome(args)

    with pytest.raises(SystemExit) as end:
        demo_main('demo', lambda argv: ('parsed', argv), run, ['--out', 'x'])
    assert end.value.code == code
    assert seen == [('parsed', ['--out', 'x'])]
    assert capsys.readouterr().err == err


def test_interrupted_is_the_shells_code_for_ctrl_c():
    assert INTERRUPTED_EXIT == 128 + signal.SIGINT
