"""Stage's blobfinder (stage_lite.model.blobfinder, its rays through sight.py): its properties,
its scan, and the blobs it makes of the scan."""
import math

import pytest
from stage_lite.model.blobfinder import Blob, Blobfinder, colour_match
from stage_lite.model.sight import Sight
from stage_lite.model.world import WorldError, load_world

BLUE = (0.0, 0.0, 1.0, 1.0)
RED = (1.0, 0.0, 0.0, 1.0)


class Scene:
    """A robot at (0, 0) facing +x with a blobfinder, and what the test puts around it."""

    def __init__(self, tmp_path, around, finder='colors_count 1 colors [ "blue" ]',
                 top='resolution 0.02'):
        p = tmp_path / 'w.world'
        p.write_text('%s\nposition( name "me" pose [ 0 0 0 0 ] size [ 0.4 0.4 0.25 ]'
                     ' blobfinder( %s ) )\n%s\n' % (top, finder, around))
        self.world = load_world(str(p))
        self.sight = Sight(self.world.models, self.world.robots, self.world.space)
        self.finder = next(m for m in self.world.models if isinstance(m, Blobfinder))

    @property
    def layer(self):
        return (self.world.updates + 1) % 2

    def blobs(self):
        return self.finder.update(self.sight, self.layer)

    def scan(self):
        return self.finder.scan(self.sight, self.layer)


def box(x, y, colour, extra=''):
    return 'model( pose [ %s %s 0 0 ] size [ 0.5 0.5 0.5 ] color "%s" %s )' % (x, y, colour,
                                                                                extra)


def test_defaults_are_stages():
    b = Blobfinder('', None, 'blobfinder', 0, 0, {})
    assert (b.scan_width, b.scan_height, b.range, b.pan, b.colors) == (80, 60, 12.0, 0.0, [])
    assert b.fov == pytest.approx(math.pi / 3, abs=1e-15)
    assert b.blocks == []


def test_properties_are_read_as_stage_reads_them(tmp_path):
    # range is a plain number: unit_length does not apply to it
    s = Scene(tmp_path, '', 'image [ 40 30 ] range 5 fov 90 pan 10 colors_count 2'
              ' colors [ "blue" "red" "green" ]', top='resolution 2 unit_length "cm"')
    f = s.finder
    assert (f.scan_width, f.scan_height, f.range) == (40, 30, 5.0)
    assert (f.fov, f.pan) == pytest.approx((math.pi / 2, math.radians(10)), abs=1e-15)
    assert f.colors == [BLUE, RED]     # the first colors_count names
    assert not [w for w in s.world.warnings if 'not used' in w]


def test_colors_count_without_colors_is_not_read(tmp_path):
    s = Scene(tmp_path, '', 'colors_count 2')
    assert s.finder.colors == []
    assert [w for w in s.world.warnings if 'colors_count is defined but not used' in w]


@pytest.mark.parametrize('finder, what', [
    ('colors_count 3 colors [ "blue" "red" ]', 'colors has 2 names'),
    ('image [ -1 60 ]', 'must be >= 0'),
    ('image [ 80 ]', 'needs 2 values'),
])
def test_what_stage_cannot_load_is_refused(tmp_path, finder, what):
    with pytest.raises(WorldError, match=what):
        Scene(tmp_path, '', finder)


def test_a_box_in_view_makes_one_blob_of_its_channel(tmp_path):
    # the box's near face at x = 1.75, 0.5 m wide: +-8.13 degrees, 22 rays of 60/79 degrees
    s = Scene(tmp_path, box(2, 0, 'blue'))
    [b] = s.blobs()
    assert b.color == BLUE
    assert b.left + b.right == 79                    # centred in the image
    width = b.right - b.left + 1
    assert 22 <= width <= 24                         # give or take a cell at each corner
    assert 1.74 <= b.range <= 1.78
    rows = int(math.atan2(0.3, b.range) / (math.pi / 3 / 60))
    assert (b.top, b.bottom) == (30 - rows, 30 + rows) == (21, 39)
    # the blob is its rays': the mean range of the rays that hit the box
    ranges, hits = s.scan()
    first, last = 79 - b.right, 79 - b.left
    assert set(hits[first:last + 1].tolist()) == {s.world.models[-1].index}
    assert hits[first - 1] == -1 and hits[last + 1] == -1
    assert b.range == pytest.approx(float(ranges[first:last + 1].mean()), rel=1e-15)


def test_a_box_to_the_left_is_on_the_images_left(tmp_path):
    [b] = Scene(tmp_path, box(2, 0.6, 'blue')).blobs()
    assert b.right < 40


def test_other_colours_are_not_reported(tmp_path):
    assert Scene(tmp_path, box(2, 0, 'red')).blobs() == []
    assert Scene(tmp_path, box(2, 0, 'red'), '').blobs()[0].color == RED     # no channels


def test_two_channels(tmp_path):
    blobs = Scene(tmp_path, box(2, 1, 'blue') + box(2, -1, 'red'),
                  'colors_count 2 colors [ "blue" "red" ]').blobs()
    # the scan runs from the right: the red box (at -y) first
    assert [b.color for b in blobs] == [RED, BLUE]
    assert blobs[0].left > blobs[1].right


def test_the_ray_after_a_blob_is_skipped(tmp_path):
    # a red and a blue box side by side: the first ray on the blue one is not part of its blob
    s = Scene(tmp_path, box(2, -0.25, 'red') + box(2, 0.25, 'blue'), '')
    _, hits = s.scan()
    red, blue = s.world.models[-2].index, s.world.models[-1].index
    red_rays = [k for k, m in enumerate(hits) if m == red]
    blue_rays = [k for k, m in enumerate(hits) if m == blue]
    assert blue_rays[0] == red_rays[-1] + 1         # they touch in the scan
    red_blob, blue_blob = s.blobs()
    assert (red_blob.color, blue_blob.color) == (RED, BLUE)
    assert 79 - red_blob.left == red_rays[-1]
    assert 79 - blue_blob.right == blue_rays[0] + 1   # STAGE_BLOB_SKIPS_NEXT_RAY
    assert 79 - blue_blob.left == blue_rays[-1]


def test_boxes_of_one_colour_side_by_side_make_one_blob(tmp_path):
    # the same two boxes, the same colour: one blob across both
    [b] = Scene(tmp_path, box(2, -0.25, 'blue') + box(2, 0.25, 'blue')).blobs()
    assert b.left + b.right == 79


def test_heights_do_not_matter(tmp_path):
    # a 5 cm box under the blobfinder's 0.25 m is seen; blob_return 0 hides nothing in 4.3.0
    low = 'model( pose [ 2 0 0 0 ] size [ 0.5 0.5 0.05 ] color "blue" blob_return 0 )'
    assert len(Scene(tmp_path, low).blobs()) == 1


def test_range_and_pan(tmp_path):
    assert Scene(tmp_path, box(2, 0, 'blue'), 'range 1.5').blobs() == []
    assert Scene(tmp_path, box(0, 2, 'blue'), 'colors_count 1 colors [ "blue" ]'
                 ' pan 90').blobs() != []
    assert Scene(tmp_path, box(2, 0, 'blue'), 'colors_count 1 colors [ "blue" ]'
                 ' pan 90').blobs() == []


def test_a_wall_hides_a_box_behind_it(tmp_path):
    s = Scene(tmp_path, box(3, 0, 'blue') + 'model( pose [ 1.5 0 0 0 ] size [ 0.1 2 0.1 ]'
              ' color "gray" )')
    assert s.blobs() == []


def test_a_robot_is_seen_where_it_drove_in_its_colour(tmp_path):
    s = Scene(tmp_path, 'position( name "other" pose [ 2 -1 0 90 ] size [ 0.4 0.4 0.25 ]'
              ' color "green" )', '')
    s.world.set_command(1, 1.0, 0.0, 0.0)
    for _ in range(10):
        s.world.step()
    [b] = s.blobs()
    assert b.color == (0.0, 1.0, 0.0, 1.0)
    assert abs(b.left + b.right - 79) <= 1              # now straight ahead
    s.world.models[-1].color = BLUE                       # SetColor: read at each update
    assert s.blobs()[0].color == BLUE


def test_a_one_ray_image_sees_nothing(tmp_path):
    # Stage's ray angle is 0 * fov / 0: NaN, and that ray walks no cell
    assert Scene(tmp_path, box(2, 0, 'blue'), 'image [ 1 60 ]').blobs() == []


def test_colour_match_ignores_alpha_and_tiny_differences():
    assert colour_match((0.5, 0.5, 0.5, 1.0), (0.5 + 9e-6, 0.5, 0.5, 0.0))
    assert not colour_match((0.5, 0.5, 0.5, 1.0), (0.5, 0.5, 0.5 + 2e-5, 1.0))


def test_blob_fields():
    assert Blob(BLUE, 1, 2, 3, 4, 5.0).range == 5.0
