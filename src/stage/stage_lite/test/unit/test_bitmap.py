"""Floor-plan bitmaps: PGM/PNG reading, threshold, bbox-of-occupied scaling, y down, rotation,
boundary, bad files."""
import math

import numpy as np
import pytest
from stage_lite.bitmap import GridSpec, Placement, load_image, rasterise
from stage_lite.worldfile import WorldError


def pgm(path, img, binary=True):
    h, w = img.shape
    if binary:
        path.write_bytes(b'P5\n# a comment\n%d %d\n255\n' % (w, h) + img.astype(np.uint8).tobytes())
    else:
        body = '\n'.join(' '.join(str(v) for v in row) for row in img)
        path.write_text('P2\n%d %d\n255\n%s\n' % (w, h, body))
    return str(path)


@pytest.mark.parametrize('binary', [True, False])
def test_threshold_127_is_occupied(tmp_path, binary):
    img = np.array([[0, 127, 128, 206, 255]])
    occ = load_image(pgm(tmp_path / 'm.pgm', img, binary))
    assert occ.tolist() == [[True, True, False, False, False]]


def test_png(tmp_path):
    from PIL import Image
    Image.fromarray(np.array([[0, 255], [255, 100]], np.uint8)).save(tmp_path / 'm.png')
    assert load_image(str(tmp_path / 'm.png')).tolist() == [[True, False], [False, True]]


@pytest.mark.parametrize('content, what', [
    (None, 'does not exist'),
    (b'hello, not an image', 'not an image'),
    (b'P5\n4 4\n255\n\x00', 'truncated'),
])
def test_bad_files_name_the_file(tmp_path, content, what):
    p = tmp_path / 'bad.pgm'
    if content is not None:
        p.write_bytes(content)
    with pytest.raises(WorldError) as e:
        load_image(str(p))
    assert str(e.value).startswith(str(p)) and what in str(e.value)


def block_image():
    """10 x 10 free image; occupied pixels only in rows 5..6, columns 3..6 (4 x 2 px)."""
    img = np.zeros((10, 10), bool)
    img[5:7, 3:7] = True
    img[5, 3] = True
    return img


def occupied_box(mask, spec):
    rows, cols = np.nonzero(mask)
    r = spec.resolution
    return (spec.origin_x + cols.min() * r, spec.origin_x + (cols.max() + 1) * r,
            spec.origin_y + rows.min() * r, spec.origin_y + (rows.max() + 1) * r)


SPEC = GridSpec.covering(-10, -10, 10, 10, 0.5)


@pytest.mark.parametrize('yaw_deg, box', [
    (0, (-3, 5, 0, 4)),          # the 4 x 2 px bbox stretched to 8 x 4 m, centred on (1, 2)
    (90, (-1, 3, -2, 6)),
    (180, (-3, 5, 0, 4)),
    (-90, (-1, 3, -2, 6)),
])
def test_bbox_of_occupied_pixels_scaled_centred_rotated(yaw_deg, box):
    pl = Placement.of(block_image(), 8.0, 4.0, 1.0, 2.0, math.radians(yaw_deg))
    mask = rasterise(pl, SPEC)
    assert occupied_box(mask, SPEC) == pytest.approx(box, abs=1e-9)
    assert mask.sum() == 16 * 8


def test_image_y_points_down():
    img = np.zeros((2, 3), bool)
    img[0, :] = True            # top row occupied, bottom row occupied only at the left
    img[1, 0] = True
    pl = Placement.of(img, 3.0, 2.0, 0.0, 0.0, 0.0)
    spec = GridSpec.covering(-2, -2, 2, 2, 0.5)
    mask = rasterise(pl, spec)

    def at(x, y):
        return mask[int((y - spec.origin_y) / 0.5), int((x - spec.origin_x) / 0.5)]
    assert at(1.2, 0.7) and not at(1.2, -0.7) and at(-1.2, -0.7)


def test_general_yaw_rotates_about_the_centre():
    pl = Placement.of(np.ones((1, 1), bool), 4.0, 0.5, 0.0, 0.0, math.radians(45))
    spec = GridSpec.covering(-3, -3, 3, 3, 0.05)
    mask = rasterise(pl, spec)

    def at(x, y):
        return mask[int((y - spec.origin_y) / 0.05), int((x - spec.origin_x) / 0.05)]
    assert at(1.2, 1.2) and at(-1.2, -1.2) and not at(1.2, -1.2) and not at(2.0, 0.0)


def test_boundary_adds_one_cell_walls_round_the_box():
    img = np.zeros((4, 4), bool)
    img[0, 0] = img[3, 3] = True
    pl = Placement.of(img, 4.0, 4.0, 0.0, 0.0, 0.0)
    spec = GridSpec.covering(-3, -3, 3, 3, 0.5)
    plain = rasterise(pl, spec)
    walled = rasterise(pl, spec, boundary=True)
    assert plain.sum() == 2 * 4
    assert walled.sum() == 28 + 2    # the 8 x 8 ring, plus each corner pixel's inner cell
    assert occupied_box(walled, spec) == pytest.approx((-2, 2, -2, 2))


def test_pixels_smaller_than_cells_are_not_lost():
    img = np.zeros((100, 100), bool)
    img[:, 50] = True                # a one-pixel line, 1 cm wide on a 1 m image
    img[0, 0] = img[-1, -1] = True
    pl = Placement.of(img, 1.0, 1.0, 0.0, 0.0, 0.0)
    spec = GridSpec.covering(-1, -1, 1, 1, 0.1)
    mask = rasterise(pl, spec)
    assert mask[:, int((0.005 - spec.origin_x) / 0.1)].sum() == 10
