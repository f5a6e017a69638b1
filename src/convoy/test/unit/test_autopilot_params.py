"""Unit tests of convoy.autopilot_params: which name is read, and the deprecation warning."""
import pytest
from convoy.autopilot_params import NAMES, OLD_NAMES, NameChoice, choose_name


@pytest.mark.parametrize('name, set_names, read, warned_words', [
    # Neither set: the new name (its default applies), no warning.
    ('speed_mps', set(), 'speed_mps', None),
    # The new name only.
    ('speed_mps', {'speed_mps'}, 'speed_mps', None),
    # The old name only: read it, and say the new name.
    ('speed_mps', {'speed'}, 'speed', ['~speed is deprecated', 'rename it ~speed_mps']),
    ('max_turn_radps', {'max_turn'}, 'max_turn', ['~max_turn is deprecated',
                                                  '~max_turn_radps']),
    ('centre_y_m', {'centre_y', 'centre_x'}, 'centre_y', ['~centre_y_m']),
    # Both: the new name wins, the old one is reported as ignored.
    ('lookahead_m', {'lookahead', 'lookahead_m'}, 'lookahead_m',
     ['~lookahead is deprecated and ignored', '~lookahead_m is set too']),
    # Another parameter's old name does not count.
    ('half_width_m', {'half_height', 'speed'}, 'half_width_m', None),
])
def test_choose_name(name, set_names, read, warned_words):
    choice = choose_name(name, set_names.__contains__)
    assert choice.read == read
    if warned_words is None:
        assert choice.warning is None
    else:
        for words in warned_words:
            assert words in choice.warning


def test_every_name_has_a_unit_suffix_and_one_old_name():
    assert set(OLD_NAMES.values()) == set(NAMES)
    assert len(OLD_NAMES) == len(NAMES)
    for old, new in OLD_NAMES.items():
        assert new.startswith(old + '_')
        assert new.rpartition('_')[2] in ('m', 'mps', 'radps')


@pytest.mark.parametrize('old', sorted(OLD_NAMES))
def test_each_old_name_alone_is_read_with_a_warning(old):
    choice = choose_name(OLD_NAMES[old], {old}.__contains__)
    assert choice == NameChoice(old, '~%s is deprecated: rename it ~%s (same value and unit)'
                                % (old, OLD_NAMES[old]))


@pytest.mark.parametrize('name', ['speed', 'speed_kmh', '', '~speed_mps'])
def test_unknown_name_is_an_error(name):
    with pytest.raises(ValueError, match='unknown autopilot parameter'):
        choose_name(name, lambda _: False)
