"""stageros's command line: flags anywhere before the world file, which comes last."""
import pytest
from stage_lite.node.stageros_args import USAGE, ArgsError, parse_args


@pytest.mark.parametrize('argv, world, gui, umn, ignored', [
    (['w.world'], 'w.world', True, False, ()),
    (['-g', 'w.world'], 'w.world', False, False, ()),
    (['-u', 'w.world'], 'w.world', True, True, ()),
    (['-g', '-u', 'w.world'], 'w.world', False, True, ()),
    (['-u', '-g', '/a/b c.world'], '/a/b c.world', False, True, ()),
    (['-x', '-g', 'junk', 'w.world'], 'w.world', False, False, ('-x', 'junk')),
    (['-g', '-g', 'w.world'], 'w.world', False, False, ()),
])
def test_flags_before_the_world_file(argv, world, gui, umn, ignored):
    args = parse_args(argv)
    assert (args.world_path, args.gui, args.use_model_names, args.ignored) == \
        (world, gui, umn, ignored)


@pytest.mark.parametrize('argv, words', [
    ([], 'no world file'),
    (['w.world', '-g'], 'must be the last'),
    (['-u'], 'must be the last'),
    (['  '], 'empty'),
])
def test_bad_command_lines_name_the_problem_and_the_usage(argv, words):
    with pytest.raises(ArgsError) as err:
        parse_args(argv)
    message = str(err.value)
    assert words in message
    assert USAGE in message
    assert '\n' not in message  # one line: stageros prints it as its one FATAL line
