"""The Stage worlds bench's copies (bench/stage_worlds_bench.py): a world of your own
(--world) named as one of Stage's must not write through the mirror's link into the worlds
folder (it once emptied four of them)."""
import importlib.util
import pathlib

BENCH = pathlib.Path(__file__).resolve().parents[2] / 'bench' / 'stage_worlds_bench.py'


def load_bench():
    spec = importlib.util.spec_from_file_location('stage_worlds_bench', BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_an_own_world_named_as_a_mirrored_one_leaves_the_original_alone(tmp_path):
    bench = load_bench()
    worlds = tmp_path / 'worlds'
    worlds.mkdir()
    (worlds / 'large.world').write_text('resolution 0.02\n# Stage\'s own\n')
    (worlds / 'bitmaps').mkdir()
    mirror = tmp_path / 'mirror'
    bench.mirror(str(worlds), str(mirror))
    assert (mirror / 'large.world').is_symlink()
    mine = tmp_path / 'mine' / 'large.world'
    mine.parent.mkdir()
    mine.write_text('resolution 0.05\n# mine\n')
    bench.own_copy(str(mine), str(mirror / 'large.world'))
    assert (worlds / 'large.world').read_text() == 'resolution 0.02\n# Stage\'s own\n'
    assert not (mirror / 'large.world').is_symlink()
    assert (mirror / 'large.world').read_text() == 'resolution 0.05\n# mine\n'
    # the copy of a mirrored world onto its own link: the world's text, the original kept
    bench.mirror(str(worlds), str(tmp_path / 'again'))
    bench.own_copy(str(worlds / 'large.world'), str(tmp_path / 'again' / 'large.world'))
    assert (worlds / 'large.world').read_text() == 'resolution 0.02\n# Stage\'s own\n'
    assert (tmp_path / 'again' / 'large.world').read_text() == (worlds / 'large.world').read_text()
