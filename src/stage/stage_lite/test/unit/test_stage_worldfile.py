"""Stage's world-file rules (stage_lite.model.worldfile_syntax and .worldfile): tokens, macros,
includes, readers, leniency, and one clear line for what Stage refuses."""
import math

import pytest
from stage_lite.model.worldfile import WorldError, Worldfile, c_atof, c_atoi
from stage_lite.model.worldfile_syntax import NUM, STRING, WORD, tokenize

DEG = math.pi / 180.0


def write(tmp_path, name, text):
    p = tmp_path / name
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text)
    return str(p)


@pytest.mark.parametrize('text, value', [
    ('12', 12), ('-3', -3), (' +7x', 7), ('1.9', 1), ('.5', 0), ('abc', 0), ('', 0)])
def test_atoi_reads_as_c_does(text, value):
    assert c_atoi(text) == value


@pytest.mark.parametrize('text, value', [
    ('0.5', 0.5), ('-2.', -2.0), ('.25', 0.25), ('1e3', 1000.0), ('3.5m', 3.5),
    ('abc', 0.0), ('-', 0.0), ('1.5.3', 1.5), ('0x10', 16.0), ('  -4', -4.0)])
def test_atof_reads_as_c_does(text, value):
    assert c_atof(text) == value


def test_tokens_words_numbers_strings_and_no_exponent(tmp_path):
    path = write(tmp_path, 'w.world', 'a 1 -2.5e1 "s t" point[0] [ 3 ] # gone\nb')
    toks = [(t.kind, t.text) for t in tokenize(path) if t.kind in (WORD, NUM, STRING)]
    # Stage's numbers are the characters +-.0-9 only: '-2.5e1' is -2.5 then a word e1
    assert toks == [(WORD, 'a'), (NUM, '1'), (NUM, '-2.5'), (WORD, 'e1'), (STRING, 's t'),
                    (WORD, 'point[0]'), (NUM, '3'), (WORD, 'b')]


def test_macro_instances_reread_the_define_and_override_it(tmp_path):
    path = write(tmp_path, 'w.world',
                 'define base position ( size [1 2 3] color "red" drive "omni" )\n'
                 'define bot base ( color "blue"\n ranger( sensor( samples 5 ) ) )\n'
                 'bot( name "a" color "green" pose [1 2 0 90] )\n'
                 'bot( name "b" )')
    wf = Worldfile(path)
    kinds = [(e.index, e.parent, e.kind) for e in wf.entities[1:]]
    # each instance: its position entity, then the define's ranger and sensor entities
    assert kinds == [(1, 0, 'position'), (2, 1, 'ranger'), (3, 2, 'sensor'),
                     (4, 0, 'position'), (5, 4, 'ranger'), (6, 5, 'sensor')]
    assert wf.read_string(1, 'color', '') == 'green' and wf.read_string(4, 'color', '') == 'blue'
    assert wf.read_tuple(1, 'size', 'lll') == [1.0, 2.0, 3.0]
    assert wf.read_tuple(1, 'pose', 'llla')[3] == 90 * DEG
    assert wf.read_int(3, 'samples', 1) == 5
    assert (wf.entities[4].path, wf.entities[4].line) == (path, 5)


def test_first_definition_of_a_macro_wins(tmp_path):
    path = write(tmp_path, 'w.world', 'define m model ( size [1 1 1] )\n'
                                      'define m position ( size [2 2 2] )\nm( )')
    wf = Worldfile(path)
    assert wf.entities[1].kind == 'model'
    assert wf.read_tuple(1, 'size', 'lll') == [1.0, 1.0, 1.0]


def test_includes_are_relative_to_the_main_world_file(tmp_path):
    # Stage resolves every include from the main world's directory, even inside sub/
    write(tmp_path, 'sub/inc.inc', 'define thing model ( size [2 2 2] )\ninclude "other.inc"')
    write(tmp_path, 'other.inc', 'define other model ( )')
    path = write(tmp_path, 'w.world', 'include "sub/inc.inc" this is ignored\t\nthing( )\t\n'
                                      'other( ) ')
    wf = Worldfile(path)
    assert [e.kind for e in wf.entities[1:]] == ['model', 'model']


def test_later_property_wins_and_units(tmp_path):
    path = write(tmp_path, 'w.world', 'unit_length "cm"\nunit_angle "radians"\n'
                                      'model( size [10 20 30] size [100 200 300]'
                                      ' pose [0 0 0 1.5] )')
    wf = Worldfile(path)
    assert wf.read_tuple(1, 'size', 'lll') == [1.0, 2.0, 3.0]
    assert wf.read_tuple(1, 'pose', 'llla')[3] == 1.5


def test_tuples_read_as_far_as_needed_with_a_warning(tmp_path):
    path = write(tmp_path, 'w.world', 'position( odom_error [0.1 0.2 0 4 0 0] )')
    wf = Worldfile(path)
    assert wf.read_tuple(1, 'odom_error', 'llla') == [0.1, 0.2, 0.0, 4 * DEG]
    assert wf.warnings == ['%s:1: property odom_error has 6 values; Stage reads the first 4'
                           % path]


def test_short_tuple_is_an_error_as_stage_exits(tmp_path):
    path = write(tmp_path, 'w.world', 'model(\n pose [1 2 45] )')
    wf = Worldfile(path)
    with pytest.raises(WorldError, match=r'w\.world:2: property pose needs 4 values, got 3'):
        wf.read_tuple(1, 'pose', 'llla')


def test_unused_properties_draw_stage_warning_once(tmp_path):
    path = write(tmp_path, 'w.world',
                 'define fp model ( laser_return 1 )\nfp( )\nfp( )\nresolution 0.02')
    wf = Worldfile(path)
    wf.read_float(0, 'resolution', 0.02)
    assert wf.unused_warnings() == ['%s:1: property laser_return is defined but not used'
                                    % path]


def test_read_values_gives_every_value_as_written_and_marks_them_read(tmp_path):
    path = write(tmp_path, 'w.world', 'window( center [ -1.5 "x" ] scale 28.8 )\nctrl "wander"')
    wf = Worldfile(path)
    assert wf.read_values(1, 'center') == ['-1.5', 'x']
    assert wf.read_values(1, 'scale') == ['28.8'] and wf.read_values(1, 'size') is None
    assert wf.unused_warnings() == ['%s:2: property ctrl is defined but not used' % path]


@pytest.mark.parametrize('text, line, what', [
    ('model( size [1 2 )', 1, 'tuple of size'),
    ('model( size\n [1 2 3] )', 1, 'the value of size must be on its line'),
    ('model( size [1 2\n 3] )', 1, 'tuple of size'),
    ('model(\n size [1 2 3] ', 1, "missing ')'"),
    ('model( name "open )', 1, 'unterminated string'),
    ('model( drive diff )', 1, 'neither a property'),
    ('define x ( )', 1, 'missing name in macro definition'),
    ('define a b c ( )', 1, 'extra tokens'),
    ('\nmodel( @ )', 2, "unexpected character '@'"),
    ('model( ) 3', 1, 'unexpected "3" at the top level'),
    ('include "nope.inc"', 1, 'cannot include'),
    ('test 1', None, 'this is a test file'),
])
def test_what_stage_refuses_is_one_clear_line(tmp_path, text, line, what):
    path = write(tmp_path, 'bad.world', text)
    with pytest.raises(WorldError) as e:
        Worldfile(path)
    msg = str(e.value)
    assert msg.startswith('%s:%d: ' % (path, line) if line else path) and what in msg
    assert '\n' not in msg


def test_include_loop(tmp_path):
    write(tmp_path, 'a.inc', 'include "b.inc"\n')
    write(tmp_path, 'b.inc', '\ninclude "a.inc"\n')
    path = write(tmp_path, 'w.world', 'include "a.inc"\n')
    with pytest.raises(WorldError, match=r'b\.inc:2: cannot include .*a\.inc: include loop'):
        Worldfile(path)


def test_missing_world_file(tmp_path):
    with pytest.raises(WorldError, match='does not exist'):
        Worldfile(str(tmp_path / 'none.world'))


def test_crlf_and_tabs_and_no_final_newline(tmp_path):
    path = write(tmp_path, 'w.world', 'resolution\t0.05\r\nmodel(\r\n\tsize [1 1 1]\r\n)')
    wf = Worldfile(path)
    assert wf.read_float(0, 'resolution', 0.02) == 0.05
    assert wf.prop(1, 'size').line == 3
