"""stage_lite.view.camera: Stage's view of the world, its window block, the mouse's pan and zoom."""
import math

import numpy as np
import pytest
from stage_lite.view.camera import (
    DEFAULT_SIZE_PX,
    MAX_SCALE,
    MIN_SIZE_PX,
    ZOOM_STEP,
    Camera,
    robots_box,
    window_camera,
    window_size,
)

TOL = 1e-9


def test_the_centre_is_the_middle_of_the_window_and_y_grows_up():
    camera = Camera(2.0, 1.0, 10.0, 0.0, 200, 100)
    np.testing.assert_allclose(camera.to_px([(2.0, 1.0), (3.0, 1.0), (2.0, 2.0)]),
                               [(100, 50), (110, 50), (100, 40)], atol=TOL)


def test_yaw_turns_the_view_the_other_way_and_to_world_undoes_to_px():
    # Stage draws with glRotatef(-yaw): at yaw 30 the world's +x points 30 degrees below
    # the screen's +x
    camera = Camera(0.0, 0.0, 100.0, 30.0, 400, 400)
    (x, y), = camera.to_px([(1.0, 0.0)]).tolist()
    assert math.degrees(math.atan2(-(y - 200), x - 200)) == pytest.approx(-30.0, abs=TOL)
    points = np.array([(0.3, -1.2), (5.0, 7.0)])
    np.testing.assert_allclose(camera.to_world(camera.to_px(points)), points, atol=TOL)
    a, b, c, d, e, f = camera.affine_to_world()
    np.testing.assert_allclose([a * 10 + b * 20 + c, d * 10 + e * 20 + f],
                               camera.to_world([(10, 20)])[0], atol=TOL)


@pytest.mark.parametrize('yaw', [0.0, -1.56, 120.0])
def test_a_drag_moves_the_world_with_the_pointer(yaw):
    camera = Camera(-12.5, 22.5, 28.806, yaw, 745, 448)
    grabbed = camera.to_world([(300, 200)])
    panned = camera.panned(40, -25)
    np.testing.assert_allclose(panned.to_px(grabbed), [(340, 175)], atol=1e-6)
    assert panned.scale == camera.scale and panned.yaw_deg == yaw


def test_the_wheel_zooms_about_the_pointer_and_stays_in_bounds():
    camera = Camera(0.0, 0.0, 20.0, 15.0, 600, 400)
    under = camera.to_world([(100, 300)])
    zoomed = camera.zoomed(2, (100, 300))
    assert zoomed.scale == pytest.approx(20.0 * ZOOM_STEP ** 2, abs=TOL)
    np.testing.assert_allclose(zoomed.to_px(under), [(100, 300)], atol=1e-6)
    assert zoomed.zoomed(-2, (100, 300)).scale == pytest.approx(20.0, abs=TOL)
    assert camera.zoomed(10_000, (0, 0)).scale == MAX_SCALE


def test_resizing_keeps_the_centre_and_the_scale():
    camera = Camera(1.0, 2.0, 30.0, 5.0, 600, 400).resized(800, 300)
    assert (camera.center_x, camera.center_y, camera.scale, camera.size_px) == \
        (1.0, 2.0, 30.0, (800, 300))
    np.testing.assert_allclose(camera.to_px([(1.0, 2.0)]), [(400, 150)], atol=TOL)


@pytest.mark.parametrize('window, screen, expected', [
    (None, None, DEFAULT_SIZE_PX),
    ({'size': [745.0, 448.0]}, None, (745, 448)),
    ({'size': [745.0, 448.0]}, (640, 480), (640, 448)),    # never beyond the screen
    ({'size': [-1.0, 300.0]}, (1024, 768), (1024, 300)),   # negative: the screen's (Stage)
    ({'size': [20.0, 20.0]}, None, (MIN_SIZE_PX, MIN_SIZE_PX)),
    ({'size': 'big'}, None, DEFAULT_SIZE_PX),
    ({'size': [math.nan, 300.0]}, None, DEFAULT_SIZE_PX),
])
def test_window_size(window, screen, expected):
    assert window_size(window, screen) == expected


def test_window_camera_takes_what_the_block_gives():
    window = {'center': [-12.5, 22.5], 'rotate': [0.0, -1.56], 'scale': 28.806}
    camera = window_camera(window, (745, 448), (0, 0, 1, 1))
    assert camera == Camera(-12.5, 22.5, 28.806, -1.56, 745, 448)


def test_window_camera_puts_the_robots_in_view_where_the_block_says_nothing():
    box = robots_box([(-11.5, 23.5), (-13.5, 21.5)], (-50, -50, 50, 50))
    camera = window_camera({'scale': 28.806}, (745, 448), box)   # the lesson's original
    assert (camera.center_x, camera.center_y) == (-12.5, 22.5)   # Stage would show (0, 0)
    fitted = window_camera(None, (600, 400), box)
    x0, y0, x1, y1 = box
    corners = fitted.to_px([(x0, y0), (x1, y1)])
    assert corners.min() >= -TOL and corners[:, 0].max() <= 600 + 1e-6 \
        and corners[:, 1].max() <= 400 + 1e-6
    assert window_camera({'scale': -3.0}, (600, 400), box).scale == fitted.scale


def test_robots_box_without_robots_is_the_floor():
    assert robots_box([], (-1, -2, 3, 4)) == (-1, -2, 3, 4)
