"""Floor-plan images as Stage reads them (stage_lite.model.image): the first channel as FLTK
gives it for each format, and the outline polygons Stage traces from the occupied pixels."""
import numpy as np
import pytest
from PIL import Image
from stage_lite.model.image import boundary_edges, first_channel, occupied, polygons
from stage_lite.model.worldfile import WorldError


def pgm(tmp_path, name, magic, w, h, maxval, body):
    p = tmp_path / name
    p.write_bytes(b'%s\n# comment\n%d %d\n%d\n' % (magic, w, h, maxval) + body)
    return str(p)


def test_binary_pgm_below_256_is_taken_raw_not_rescaled(tmp_path):
    # FLTK copies P5 bytes when maxval < 256: with maxval 15, 14 ("almost white") is dark
    path = pgm(tmp_path, 'a.pgm', b'P5', 3, 1, 15, bytes([0, 14, 15]))
    assert first_channel(path).tolist() == [[0, 14, 15]]
    assert occupied(first_channel(path)).all()


def test_16_bit_and_ascii_pgm_are_scaled_in_integers(tmp_path):
    path = pgm(tmp_path, 'b.pgm', b'P5', 2, 1, 1000, (255).to_bytes(2, 'big')
               + (1000).to_bytes(2, 'big'))
    assert first_channel(path).tolist() == [[255 * 255 // 1000, 255]]
    path = pgm(tmp_path, 'c.pgm', b'P2', 3, 1, 1000, b'499 500 1000\n')
    assert first_channel(path).tolist() == [[127, 127, 255]]


def test_pbm_set_bits_read_white_as_fltk_reads_them(tmp_path):
    p = tmp_path / 'd.pbm'
    p.write_bytes(b'P4\n3 1\n' + bytes([0b10100000]))
    assert first_channel(str(p)).tolist() == [[255, 0, 255]]


@pytest.mark.parametrize('mode, pixels, expected', [
    ('RGB', [(255, 0, 0), (0, 0, 255), (128, 0, 0)], [255, 0, 128]),     # red is free
    ('RGBA', [(0, 0, 0, 0), (200, 200, 200, 0), (100, 255, 255, 255)], [0, 200, 100]),
    ('L', [0, 127, 128], [0, 127, 128]),
    ('LA', [(10, 0), (250, 255), (130, 9)], [10, 250, 130]),
])
def test_png_first_channel_alpha_ignored(tmp_path, mode, pixels, expected):
    im = Image.new(mode, (3, 1))
    im.putdata(pixels)
    path = str(tmp_path / 'e.png')
    im.save(path)
    assert first_channel(path).tolist() == [expected]


def test_palette_and_16_bit_png_and_bmp(tmp_path):
    im = Image.new('P', (2, 1))
    im.putpalette([255, 0, 0, 0, 0, 255] + [0] * 762)
    im.putdata([0, 1])
    im.save(str(tmp_path / 'p.png'))
    assert first_channel(str(tmp_path / 'p.png')).tolist() == [[255, 0]]
    Image.fromarray(np.array([[300, 65535]], np.uint16)).save(str(tmp_path / 's.png'))
    assert first_channel(str(tmp_path / 's.png')).tolist() == [[1, 255]]
    Image.new('RGB', (1, 1), (90, 255, 255)).save(str(tmp_path / 'b.bmp'))
    assert first_channel(str(tmp_path / 'b.bmp')).tolist() == [[90]]


def test_missing_and_unreadable_images(tmp_path):
    with pytest.raises(WorldError, match='does not exist'):
        first_channel(str(tmp_path / 'none.png'))
    (tmp_path / 'x.png').write_bytes(b'not an image')
    with pytest.raises(WorldError, match='not an image Stage reads'):
        first_channel(str(tmp_path / 'x.png'))


def test_one_pixel_is_a_square_with_the_y_axis_flipped():
    occ = np.zeros((3, 4), bool)
    occ[1, 2] = True
    (poly,) = polygons(occ)
    # the corners of pixel (x 2, y 1), image y negated, starting at the smallest corner
    assert poly.tolist() == [[2.0, -1.0], [3.0, -1.0], [3.0, -2.0], [2.0, -2.0]]


def test_straight_runs_merge_but_not_across_the_first_point():
    occ = np.zeros((1, 3), bool)
    occ[0, :] = True
    (poly,) = polygons(occ)
    # Stage merges a point that continues the direction of the two before it; the run
    # through the seed point (0, 0) -> (1, 0) -> (2, 0) is not merged: only 2 points exist
    assert poly.tolist() == [[0.0, 0.0], [1.0, 0.0], [3.0, 0.0], [3.0, -1.0], [0.0, -1.0]]


def test_pixels_touching_at_a_corner_and_holes():
    occ = np.array([[1, 0], [0, 1]], bool)
    edges = boundary_edges(occ)
    assert len(edges) == 8
    polys = polygons(occ)
    assert sum(len(p) for p in polys) >= 8
    ring = np.ones((3, 3), bool)
    ring[1, 1] = False
    polys = polygons(ring)
    assert len(polys) == 2                  # the outside and the hole
    assert {tuple(map(tuple, p.tolist())) for p in polys} >= {((1.0, -1.0), (1.0, -2.0),
                                                               (2.0, -2.0), (2.0, -1.0))}


def test_edges_between_occupied_pixels_cancel():
    occ = np.ones((2, 2), bool)
    assert len(boundary_edges(occ)) == 8     # only the outer boundary remains
