"""Unit tests of multihost.step_pairs: a Stage step's ground truth and odom, paired by stamp."""
import pytest
from multihost.step_pairs import UNPAIRED_STEPS, StepPairs

FIELDS = ('x', 'y', 'v')


@pytest.mark.parametrize('first', [{'x': 1.0, 'y': 2.0}, {'v': 0.2}])
def test_a_step_is_whole_with_both_halves_in_either_order(first):
    pairs = StepPairs(FIELDS)
    second = {'v': 0.2} if 'x' in first else {'x': 1.0, 'y': 2.0}
    assert pairs.add('robot_0', 100, **first) is None
    assert pairs.add('robot_0', 100, **second) == {'x': 1.0, 'y': 2.0, 'v': 0.2}
    assert pairs.waiting('robot_0') == []


def test_halves_of_other_stamps_and_robots_do_not_pair():
    pairs = StepPairs(FIELDS)
    assert pairs.add('robot_0', 100, x=1.0, y=2.0) is None
    assert pairs.add('robot_0', 200, v=0.2) is None
    assert pairs.add('robot_1', 100, v=0.2) is None
    assert pairs.waiting('robot_0') == [100, 200]
    assert pairs.waiting('robot_1') == [100]


def test_a_whole_step_drops_older_halves_only():
    pairs = StepPairs(FIELDS)
    pairs.add('robot_0', 100, x=1.0, y=2.0)  # its odom was lost
    pairs.add('robot_0', 300, v=0.0)         # a later step, half here
    pairs.add('robot_0', 200, x=1.1, y=2.0)
    assert pairs.add('robot_0', 200, v=0.2) == {'x': 1.1, 'y': 2.0, 'v': 0.2}
    assert pairs.waiting('robot_0') == [300]


def test_a_silent_topic_keeps_a_bounded_number_of_halves():
    pairs = StepPairs(FIELDS)
    for k in range(3 * UNPAIRED_STEPS):
        assert pairs.add('robot_0', k, x=0.0, y=0.0) is None
    assert pairs.waiting('robot_0') == list(range(2 * UNPAIRED_STEPS, 3 * UNPAIRED_STEPS))


def test_a_later_half_overrides_the_same_field():
    pairs = StepPairs(FIELDS)
    pairs.add('robot_0', 100, v=0.1)
    pairs.add('robot_0', 100, v=0.2)
    assert pairs.add('robot_0', 100, x=0.0, y=0.0)['v'] == 0.2


def test_unknown_fields_and_bad_bounds_are_refused():
    with pytest.raises(ValueError, match='fields'):
        StepPairs(FIELDS).add('robot_0', 100, z=1.0)
    with pytest.raises(ValueError, match='unpaired_steps'):
        StepPairs(FIELDS, unpaired_steps=0)
