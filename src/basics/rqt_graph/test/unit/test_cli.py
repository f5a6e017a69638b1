"""Unit tests of rqt_graph.cli without a master: the options and their errors."""
import pytest
from rqt_graph.cli import parse_args


@pytest.mark.parametrize('argv, out, fmt, show_all', [
    ([], None, None, False),
    (['--out', 'g.png'], 'g.png', 'png', False),
    (['--out', 'g.SVG', '--all'], 'g.SVG', 'svg', True),
    (['--all', '--out=g.dot'], 'g.dot', 'dot', True),
])
def test_parse_args(argv, out, fmt, show_all):
    args = parse_args(argv)
    assert (args.out, getattr(args, 'format', None), args.all) == (out, fmt, show_all)


@pytest.mark.parametrize('argv, words', [
    (['--out', 'g.jpg'], "unknown output extension '.jpg'"),
    (['--out'], 'expected one argument'),
    (['--bogus'], 'unrecognized arguments: --bogus'),
])
def test_parse_args_errors_exit_2(argv, words, capsys):
    with pytest.raises(SystemExit) as exc:
        parse_args(argv)
    assert exc.value.code == 2
    assert words in capsys.readouterr().err
