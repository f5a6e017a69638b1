"""Pictures: walls where the grid has them, beams, trails and robots in their colours."""
import math

import numpy as np
import pytest
from course_common.save_image import write_png
from stage_lite.node import world_picture as picture
from stage_lite.node.world_picture import RangerView, RobotView, Trails

TOL = 1e-9  # m / px: plain affine maps


def _room():
    grid = np.zeros((100, 100), bool)   # 2 m square at 2 cm, walls on the border
    grid[0, :] = grid[-1, :] = grid[:, 0] = grid[:, -1] = True
    return grid, -1.0, -1.0, 0.02


def test_fit_view_keeps_the_aspect_and_margin():
    view = picture.fit_view((0, 0, 4, 2), 500, 500)
    assert view.scale == pytest.approx(500 / (4 + 2 * picture.MARGIN_M), abs=TOL)
    assert view.to_px([(view.x0, view.y1)]).tolist() == [[0.0, 0.0]]
    (px, py), = view.to_px([(0.0, 0.0)]).tolist()
    assert py > 0 and px > 0


@pytest.mark.parametrize('bounds, w, h', [((0, 0, 0, 1), 10, 10), ((0, 0, 1, 1), 0, 10)])
def test_fit_view_refuses_empty_inputs(bounds, w, h):
    with pytest.raises(ValueError):
        picture.fit_view(bounds, w, h)


@pytest.mark.parametrize('max_px', [600, 60])  # bigger than the grid, and much smaller
def test_floor_image_keeps_thin_walls(max_px):
    occ = _room()
    view = picture.fit_view(picture.world_bounds(occ), max_px, max_px)
    image = np.asarray(picture.floor_image(view, occ))
    wall = np.all(image == picture.WALL_RGB, axis=2)
    w, h = view.size_px
    (cx, cy), = view.to_px([(0.0, 0.0)]).astype(int).tolist()
    assert not wall[cy, cx]
    (lx, _), = view.to_px([(-0.99, 0.0)]).astype(int).tolist()
    assert wall[cy, lx - 1: lx + 2].any()   # the left wall survives shrinking
    assert image.shape == (h, w, 3)


def test_render_draws_robot_beams_and_trail_in_colour():
    occ = _room()
    view = picture.fit_view(picture.world_bounds(occ), 400, 400)
    base = picture.floor_image(view, occ)
    angles = np.linspace(-math.pi / 2, math.pi / 2, 31)
    robot = RobotView(pose=(0.0, 0.0, 0.0), size=(0.35, 0.35), origin=(-0.05, 0.0),
                      color=(0.0, 0.0, 1.0),
                      rangers=(RangerView((0.05, 0.0, 0.0), angles, np.full(31, 0.8)),),
                      trail=np.array([[-0.9, -0.9], [-0.5, -0.9]]))
    image = np.asarray(picture.render(view, base, [robot])).astype(int)
    assert np.array_equal(np.asarray(base), np.asarray(picture.floor_image(view, occ)))
    (cx, cy), = view.to_px([(-0.1, 0.1)]).astype(int).tolist()
    assert tuple(image[cy, cx]) == (0, 0, 255)                      # body
    (bx, by), = view.to_px([(0.6, 0.0)]).astype(int).tolist()
    alpha = round(picture.FAN_ALPHA * 255) / 255    # Pillow blends in whole steps of 1/255
    assert np.abs(image[by, bx] - np.array([255 * (1 - alpha)] * 2 + [255])).max() <= 1  # fan
    (tx, ty), = view.to_px([(-0.7, -0.9)]).astype(int).tolist()
    assert tuple(image[ty, tx]) == (0, 0, 255)                      # trail


def test_four_overlapping_fans_stay_four_fans():
    # The lesson's hall: four robots whose fans overlap. Each fan is its robot's colour laid
    # over the floor, not an opaque area: a pixel only robot k sees is tinted k's colour, a
    # pixel two fans share shows both, and a wall under a fan stays darker than the free floor.
    occ = _room()
    view = picture.fit_view(picture.world_bounds(occ), 400, 400)
    base = picture.floor_image(view, occ)
    colors = [(0, 0, 1.0), (1.0, 0, 0), (0, 1.0, 0), (1.0, 0, 1.0)]
    angles = np.linspace(-0.3, 0.3, 21)
    # 0 and 2 face each other (their fans share x in [-0.2, 0.2]); 1 and 3 face the walls
    poses = [(-0.8, 0.5, 0.0), (-0.7, -0.5, math.pi), (0.8, 0.5, math.pi), (0.7, -0.5, 0.0)]
    robots = [RobotView(pose=p, size=(0.1, 0.1), origin=(0.0, 0.0), color=c,
                        rangers=(RangerView((0.0, 0.0, 0.0), angles, np.full(21, 1.0)),))
              for p, c in zip(poses, colors, strict=True)]
    image = np.asarray(picture.render(view, base, robots)).astype(int)
    floor = np.asarray(base).astype(int)

    def at(x, y):
        (px, py), = view.to_px([(x, y)]).astype(int).tolist()
        return image[py, px], floor[py, px]
    alpha = round(picture.FAN_ALPHA * 255) / 255    # Pillow blends in whole steps of 1/255
    for (x, y, yaw), color in zip(poses, colors, strict=True):
        pixel, below = at(x + 0.25 * math.cos(yaw), y)        # in front of it: its fan only
        expected = below + alpha * (np.array(color) * 255 - below)
        assert np.abs(pixel - expected).max() <= 1, (pixel, expected)
    shared, below = at(0.0, 0.5)              # robots 0 (blue), then 2 (green): both fans
    blue = below + alpha * (np.array([0, 0, 255]) - below)
    expected = blue + alpha * (np.array([0, 255, 0]) - blue)
    assert np.abs(shared - expected).max() <= 2, (shared, expected)
    wall, below = at(-0.99, -0.5)             # the west wall, under robot 1's fan
    assert (wall < 128).all() and wall.tolist() != below.tolist()


def test_footprint_follows_origin_and_yaw():
    robot = RobotView(pose=(1.0, 2.0, math.pi / 2), size=(0.4, 0.2), origin=(-0.1, 0.0),
                      color=(1, 0, 0))
    corners = picture.footprint(robot)
    assert corners[:, 0].min() == pytest.approx(0.9, abs=TOL)
    assert corners[:, 1].min() == pytest.approx(2.0 - 0.3, abs=TOL)
    assert corners[:, 1].max() == pytest.approx(2.0 + 0.1, abs=TOL)


def test_the_floor_image_saves_as_png_in_new_directories(tmp_path):
    occ = _room()
    view = picture.fit_view(picture.world_bounds(occ), 50, 50)
    path = write_png(str(tmp_path / 'a' / 'b.png'), picture.floor_image(view, occ))
    assert path.endswith('b.png') and (tmp_path / 'a' / 'b.png').stat().st_size > 0


def test_trails_skip_tiny_steps_and_cap_their_length():
    trails = Trails(2, min_step_m=0.1, max_points=3)
    for x in (0.0, 0.05, 0.1, 0.25, 0.4, 0.55):
        trails.add(0, x, 0.0)
    assert trails.get(0)[:, 0].tolist() == pytest.approx([0.25, 0.4, 0.55], abs=TOL)
    assert trails.get(1).shape == (0, 2)
    trails.clear()
    assert trails.get(0).shape == (0, 2)
