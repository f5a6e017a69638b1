"""Pictures as Stage's window draws them: grid, walls, fans, bodies, trails, status line."""
import math
from dataclasses import replace

import numpy as np
import pytest
from course_common.save_image import write_png
from stage_lite.view import world_picture as picture
from stage_lite.view.camera import Camera
from stage_lite.view.world_picture import DrawOptions, FloorPlan, RobotView, ScanView, trails

TOL = 1e-9  # m / px: plain affine maps
ALPHA = round(picture.FAN_ALPHA * 255) / 255    # Pillow blends in whole steps of 1/255


def _room():
    grid = np.zeros((100, 100), bool)   # 2 m square at 2 cm, walls on the border
    grid[0, :] = grid[-1, :] = grid[:, 0] = grid[:, -1] = True
    return grid, -1.0, -1.0, 0.02


def _plan():
    occ = _room()
    return FloorPlan(occ, picture.world_bounds(occ))


def _camera(scale=150.0, yaw=0.0, size=(400, 400)):
    return Camera(0.0, 0.0, scale, yaw, *size)


def _at(image, camera, x, y):
    (px, py), = camera.to_px([(x, y)]).astype(int).tolist()
    return np.asarray(image).astype(int)[py, px]


def test_floor_checkers_whole_metres_inside_the_world_and_stage_grey_outside():
    plan = FloorPlan(_room(), (-1.0, -1.0, 1.0, 1.0))
    camera = _camera(scale=100.0)
    image = plan.image(camera)
    assert tuple(_at(image, camera, 0.5, 0.5)) == picture.FREE_RGB     # floor(0)+floor(0): even
    assert tuple(_at(image, camera, -0.5, 0.5)) == picture.CHECK_RGB   # -1 + 0: odd
    assert tuple(_at(image, camera, 1.5, 0.0)) == picture.OUTSIDE_RGB  # beyond the extent
    plain = plan.image(camera, grid_on=False)
    assert tuple(_at(plain, camera, -0.5, 0.5)) == picture.FREE_RGB


@pytest.mark.parametrize('scale', [180.0, 20.0])  # more pixels than cells, and far fewer
def test_floor_keeps_thin_walls(scale):
    camera = _camera(scale=scale)
    image = np.asarray(_plan().image(camera, grid_on=False))
    wall = np.all(image == picture.WALL_RGB, axis=2)
    (cx, cy), = camera.to_px([(0.0, 0.0)]).astype(int).tolist()
    assert not wall[cy, cx]
    (lx, _), = camera.to_px([(-0.99, 0.0)]).astype(int).tolist()
    assert wall[cy, lx - 1: lx + 2].any()   # the left wall survives shrinking
    assert image.shape == (400, 400, 3)


def test_floor_turns_with_the_camera():
    # yaw 90: the view turns by -90 degrees (Stage's glRotatef(-yaw)): east points down
    camera = _camera(scale=100.0, yaw=90.0)
    image = _plan().image(camera, grid_on=False)
    (wx, wy), = camera.to_px([(0.99, 0.0)]).tolist()
    assert wy == pytest.approx(200 + 99, abs=TOL) and wx == pytest.approx(200, abs=TOL)
    assert tuple(_at(image, camera, 0.99, 0.0)) == picture.WALL_RGB


def test_render_draws_body_fan_trail_and_status_on_a_copy():
    plan, camera = _plan(), _camera()
    base = plan.image(camera)
    angles = np.linspace(-math.pi / 2, math.pi / 2, 31)
    robot = RobotView(pose=(0.0, 0.0, 0.0), size=(0.35, 0.35), origin=(-0.05, 0.0),
                      color=(0.0, 0.0, 1.0),
                      scans=(ScanView((0.05, 0.0, 0.0), angles, np.full(31, 0.8)),),
                      trail=np.array([[-0.9, -0.9], [-0.5, -0.9]]))
    options = DrawOptions(trails=True)
    image = picture.render(camera, base, [robot], options, ' 0m 01s 000msec [1.0]')
    assert np.array_equal(np.asarray(base), np.asarray(plan.image(camera)))
    assert tuple(_at(image, camera, -0.1, 0.1)) == (0, 0, 255)                # body
    below = _at(base, camera, 0.6, 0.0)
    fan = below + ALPHA * (np.array([0, 0, 255]) - below)
    assert np.abs(_at(image, camera, 0.6, 0.0) - fan).max() <= 1               # fan
    assert tuple(_at(image, camera, -0.7, -0.9)) == (0, 0, 255)                # trail
    pixels = np.asarray(image)
    assert (pixels[-5:, :150] == picture.CLOCK_BOX_RGB).all(axis=2).any()     # status box
    bare = picture.render(camera, base, [robot], DrawOptions(data=False, clock=False))
    assert tuple(_at(bare, camera, 0.6, 0.0)) == tuple(below)                  # no fan
    assert tuple(_at(bare, camera, -0.7, -0.9)) != (0, 0, 255)                 # no trail
    assert not (np.asarray(bare)[-5:, :150] == picture.CLOCK_BOX_RGB).all(axis=2).any()


def test_four_overlapping_fans_stay_four_fans():
    # The lesson's hall: four robots whose fans overlap. Each fan is its robot's colour laid
    # over the floor, not an opaque area: a pixel only robot k sees is tinted k's colour, a
    # pixel two fans share shows both, and a wall under a fan stays darker than the free floor.
    camera = _camera()
    base = _plan().image(camera, grid_on=False)
    colors = [(0, 0, 1.0), (1.0, 0, 0), (0, 1.0, 0), (1.0, 0, 1.0)]
    angles = np.linspace(-0.3, 0.3, 21)
    # 0 and 2 face each other (their fans share x in [-0.2, 0.2]); 1 and 3 face the walls
    poses = [(-0.8, 0.5, 0.0), (-0.7, -0.5, math.pi), (0.8, 0.5, math.pi), (0.7, -0.5, 0.0)]
    robots = [RobotView(pose=p, size=(0.1, 0.1), origin=(0.0, 0.0), color=c,
                        scans=(ScanView((0.0, 0.0, 0.0), angles, np.full(21, 1.0)),))
              for p, c in zip(poses, colors, strict=True)]
    image = picture.render(camera, base, robots, DrawOptions(clock=False))
    for (x, y, yaw), color in zip(poses, colors, strict=True):
        x_ahead = x + 0.25 * math.cos(yaw)                # in front of it: its fan only
        below = _at(base, camera, x_ahead, y)
        expected = below + ALPHA * (np.array(color) * 255 - below)
        pixel = _at(image, camera, x_ahead, y)
        assert np.abs(pixel - expected).max() <= 1, (pixel, expected)
    below = _at(base, camera, 0.0, 0.5)      # robots 0 (blue), then 2 (green): both fans
    blue = below + ALPHA * (np.array([0, 0, 255]) - below)
    expected = blue + ALPHA * (np.array([0, 255, 0]) - blue)
    assert np.abs(_at(image, camera, 0.0, 0.5) - expected).max() <= 2
    wall, below = _at(image, camera, -0.99, -0.5), _at(base, camera, -0.99, -0.5)
    assert (wall < 128).all() and wall.tolist() != below.tolist()   # the west wall, under a fan


def test_footprint_is_the_size_rectangle_or_the_blocks():
    robot = RobotView(pose=(1.0, 2.0, math.pi / 2), size=(0.4, 0.2), origin=(-0.1, 0.0),
                      color=(1, 0, 0))
    (corners,) = picture.footprint(robot)
    assert corners[:, 0].min() == pytest.approx(0.9, abs=TOL)
    assert corners[:, 1].min() == pytest.approx(2.0 - 0.3, abs=TOL)
    assert corners[:, 1].max() == pytest.approx(2.0 + 0.1, abs=TOL)
    triangle = np.array([(0.2, 0.0), (-0.1, 0.1), (-0.1, -0.1)])
    shaped = RobotView(pose=(1.0, 2.0, math.pi / 2), size=(0.3, 0.2), origin=(0.0, 0.0),
                       color=(1, 0, 0), body=(triangle,))
    (polygon,) = picture.footprint(shaped)
    assert polygon[0].tolist() == pytest.approx([1.0, 2.2], abs=TOL)   # the tip, turned


def test_the_nose_is_drawn_with_gui_nose_only():
    camera = _camera(scale=300.0)
    base = _plan().image(camera, grid_on=False)
    robot = RobotView(pose=(0.0, 0.0, 0.0), size=(0.4, 0.4), origin=(0.0, 0.0),
                      color=(1.0, 0.0, 0.0))
    with_nose = picture.render(camera, base, [robot], DrawOptions(clock=False))
    without = picture.render(camera, base, [replace(robot, nose=False)],
                             DrawOptions(clock=False))
    assert tuple(_at(with_nose, camera, 0.1, 0.0)) == picture.OUTLINE_RGB
    assert tuple(_at(without, camera, 0.1, 0.0)) == (255, 0, 0)


def test_fan_outlines_drop_the_corners_of_straight_runs_only():
    # a fan's end points along a wall (a straight run of 41 corners) and around a corner
    wall = np.column_stack((np.arange(0, 41), np.full(41, 10)))
    side = np.column_stack((np.full(20, 40), np.arange(11, 31)))
    polygon = np.vstack(([[0, 0]], wall, side))
    kept = picture._simplified(polygon)
    assert len(kept) < len(polygon) / 4
    for corner in ([0, 0], [0, 10], [40, 10], [40, 30]):        # the shape's own corners
        assert corner in kept.tolist()
    # every dropped point lies within a pixel of the simplified outline
    for point in polygon:
        d = min(_distance_to_segment(point, a, b)
                for a, b in zip(kept[:-1], kept[1:], strict=True))
        assert d < 1.0


def _distance_to_segment(p, a, b):
    p, a, b = (np.asarray(v, float) for v in (p, a, b))
    t = np.clip(np.dot(p - a, b - a) / max(np.dot(b - a, b - a), 1e-12), 0.0, 1.0)
    return float(np.linalg.norm(p - (a + t * (b - a))))


def test_a_robot_far_too_small_to_see_is_still_a_dot():
    camera = _camera(scale=0.5)
    base = _plan().image(camera)
    robot = RobotView(pose=(0.0, 0.0, 0.0), size=(0.35, 0.35), origin=(0.0, 0.0),
                      color=(1.0, 0.0, 0.0))
    image = np.asarray(picture.render(camera, base, [robot], DrawOptions(clock=False)))
    assert (image == (255, 0, 0)).all(axis=2).sum() >= 1


@pytest.mark.parametrize('window, expected', [
    (None, DrawOptions()),
    ({'show_data': 0.0, 'show_grid': 0.0}, DrawOptions(data=False, grid=False)),
    ({'show_clock': 0.0, 'show_trailfast': 1.0}, DrawOptions(clock=False, trails=True)),
    ({'show_data': 'yes'}, DrawOptions()),          # not a number: Stage's default stays
])
def test_draw_options_follow_the_window_blocks_flags(window, expected):
    assert picture.draw_options(window) == expected


def test_the_floor_image_saves_as_png_in_new_directories(tmp_path):
    path = write_png(str(tmp_path / 'a' / 'b.png'), _plan().image(_camera(size=(50, 50))))
    assert path.endswith('b.png') and (tmp_path / 'a' / 'b.png').stat().st_size > 0


def test_trails_skip_tiny_steps_and_cap_their_length():
    paths = trails(3, min_step_m=0.1, max_points=3)
    for x in (0.0, 0.05, 0.1, 0.25, 0.4, 0.55):
        paths.add_all([[x, 0.0], [0.0, x], [math.nan, x]])    # every robot at once
    assert paths.get(0)[:, 0].tolist() == pytest.approx([0.25, 0.4, 0.55], abs=TOL)
    assert paths.get(1)[:, 1].tolist() == pytest.approx([0.25, 0.4, 0.55], abs=TOL)
    assert paths.get(2).shape == (0, 2)                      # never a finite position
    paths.add_all([[9.0, 9.0]], [2])                           # one robot alone
    assert paths.get(2).tolist() == [[9.0, 9.0]] and len(paths.get(0)) == 3
    paths.clear()
    assert paths.get(0).shape == (0, 2)
