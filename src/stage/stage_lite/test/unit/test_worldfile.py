"""The world-file reader: syntax, define chains, include, units, and every bad input."""
import math

import pytest
from stage_lite.worldfile import WorldError, parse, tokenize

ANGLE_TOL = 1e-12   # radians: degrees converted exactly


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def test_tokens_comments_strings_tuples_and_stage_words():
    toks = tokenize('a 1 -2.5e1 "s t" [ 3 ] # gone\nb( point[0] [1 2] )', 'f')
    assert [(t.kind, t.text) for t in toks] == [
        ('word', 'a'), ('number', '1'), ('number', '-2.5e1'), ('string', '"s t"'),
        ('open', '['), ('number', '3'), ('close', ']'), ('word', 'b'), ('open', '('),
        ('word', 'point[0]'), ('open', '['), ('number', '1'), ('number', '2'),
        ('close', ']'), ('close', ')')]
    assert toks[-1].line == 2


def test_define_chain_with_overrides_and_children(tmp_path):
    path = write(tmp_path, 'w.world',
                 'define base position ( size [1 2 3] color "red" drive "omni" )\n'
                 'define bot base ( color "blue"\n ranger( sensor( samples 5 ) ) )\n'
                 'bot( name "a" color "green" pose [1 2 0 90] )\n'
                 'bot( name "b" )')
    w = parse(path)
    a, b = w.models
    assert (a.kind, a.declared) == ('position', 'bot')
    assert a.text('color', '') == 'green' and b.text('color', '') == 'blue'
    assert a.tuple('size', (0, 0, 0)) == (1, 2, 3)
    assert a.text('drive', '') == 'omni'
    assert a.tuple('pose', (0, 0, 0, 0), angles=(3,))[3] == pytest.approx(math.pi / 2,
                                                                         abs=ANGLE_TOL)
    assert [c.kind for c in a.children] == ['ranger'] and a.children is not b.children
    assert a.children[0].children[0].number('samples', 1) == 5


def test_include_relative_to_including_file_and_tabs_no_final_newline(tmp_path):
    (tmp_path / 'sub').mkdir()
    write(tmp_path, 'sub/inc.inc', 'define thing model ( size [2 2 2] )\ninclude "deeper.inc"')
    write(tmp_path, 'sub/deeper.inc', 'define other model ( )')
    path = write(tmp_path, 'w.world', 'include "sub/inc.inc"\t \nthing( )\t\nother( ) ')
    w = parse(path)
    assert [m.declared for m in w.models] == ['thing', 'other']


def test_unused_properties_draw_stage_warning_once(tmp_path):
    path = write(tmp_path, 'w.world',
                 'define fp model ( laser_return 1 )\nfp( )\nfp( )\nresolution 0.02')
    w = parse(path)
    for m in w.models:
        m.prop('size')
    w.top.number('resolution', 0.02)
    assert w.unused_warnings() == ['%s:1: property laser_return is defined but not used'
                                   % path]


@pytest.mark.parametrize('text, line, what', [
    ('model( size [1 2 )', 1, 'syntax error'),
    ('model(\n size [1 2] ', 2, 'missing ")"'),
    ('\n\nrobotz( )', 3, 'unknown model type "robotz"'),
    ('model( name "open )', 1, 'unterminated string'),
    ('model( ) )', 1, 'syntax error: unexpected )'),
    ('define x ( )', 1, 'define NAME PARENT'),
    ('model( @ )', 1, "unexpected character '@'"),
    ('include "nope.inc"', 1, 'nope.inc does not exist'),
])
def test_bad_input_one_clear_line(tmp_path, text, line, what):
    path = write(tmp_path, 'bad.world', text)
    with pytest.raises(WorldError) as e:
        parse(path)
    msg = str(e.value)
    assert msg.startswith('%s:%d: ' % (path, line)) and what in msg
    assert '\n' not in msg


def test_include_loop(tmp_path):
    write(tmp_path, 'a.inc', 'include "b.inc"')
    write(tmp_path, 'b.inc', '\ninclude "a.inc"')
    path = write(tmp_path, 'w.world', 'include "a.inc"')
    with pytest.raises(WorldError, match=r'b\.inc:2: include loop'):
        parse(path)


def test_missing_world_file(tmp_path):
    with pytest.raises(WorldError, match='does not exist'):
        parse(str(tmp_path / 'none.world'))


@pytest.mark.parametrize('prop, getter', [
    ('size [1 a 2]', lambda m: m.tuple('size', (0, 0, 0))),
    ('size [1 2 3 4]', lambda m: m.tuple('size', (0, 0, 0))),
    ('boundary [1 2]', lambda m: m.number('boundary', 0)),
])
def test_bad_property_values(tmp_path, prop, getter):
    path = write(tmp_path, 'w.world', 'model(\n %s )' % prop)
    with pytest.raises(WorldError, match=r'w\.world:2: property'):
        getter(parse(path).models[0])
