"""Unit tests of turtle_lite.naming: turtlesim's name counter."""

from turtle_lite.naming import NameCounter


def test_counter_example_from_turtlesim():
    """turtle1 alive, spawn turtle3, then '' gives turtle2, '' gives turtle4, kill turtle2,
    '' gives turtle5 (turtle_frame.cpp's spawnTurtle)."""
    counter = NameCounter()
    alive = {counter.next_name(set())}
    assert alive == {'turtle1'}
    alive.add('turtle3')
    alive.add(counter.next_name(alive))
    assert 'turtle2' in alive
    name = counter.next_name(alive)
    assert name == 'turtle4'
    alive.add(name)
    alive.discard('turtle2')
    assert counter.next_name(alive) == 'turtle5'


def test_counter_reset_starts_again():
    counter = NameCounter()
    for _ in range(5):
        counter.next_name(set())
    counter.reset()
    assert counter.next_name(set()) == 'turtle1'
    assert counter.next_name({'turtle1'}) == 'turtle2'
