"""stage_lite.view.world_view: what the window and ~save_image draw from."""
import numpy as np
from stage_lite.model.world import load_world
from stage_lite.testing.room import write_room_pgm
from stage_lite.view.camera import ROBOTS_MARGIN_M
from stage_lite.view.world_picture import DrawOptions
from stage_lite.view.world_view import WorldView

WORLD = '''resolution 0.02
interval_sim 100
model( size [10 10 1] bitmap "room.pgm" pose [0 0 0 0] )
position( pose [1 2 0 0] size [0.4 0.4 0.25] color "blue" gui_nose 1
  ranger( sensor( range [0 20] fov 180 samples 5 ) ) )
'''
TRIANGLE = '''
position( pose [-2 -2 0 0] size [0.6 0.4 0.25] color "red"
  block( points 3 point[0] [0 0] point[1] [1 0.5] point[2] [0 1] z [0 1] ) )
'''


def lesson_like(tmp_path, extra=''):
    write_room_pgm(str(tmp_path / 'room.pgm'))
    (tmp_path / 'w.world').write_text(WORLD + extra)
    return load_world(str(tmp_path / 'w.world'))


def test_trails_follow_the_steps_and_reset_clears_them(tmp_path):
    world = lesson_like(tmp_path)
    view = WorldView(world)
    world.set_command(0, 1.0, 0.0, 0.0)
    for _ in range(5):
        world.step()
        view.record()
    (robot,) = view.robots()
    np.testing.assert_allclose(robot.trail[:, 0], [1.1, 1.2, 1.3, 1.4, 1.5], atol=1e-9)
    assert robot.pose[:2] == world.robots[0].pose[:2] and robot.color == (0.0, 0.0, 1.0)
    world.reset()
    view.clear()
    assert len(view.robots()[0].trail) == 0


def test_views_are_copies_taken_now(tmp_path):
    world = lesson_like(tmp_path)
    view = WorldView(world)
    world.step()
    (before,) = view.robots()
    ranges = before.scans[0].ranges.copy()
    world.robots[0].rangers[0].ranges[:] = 0.0    # the next step writes over the scan
    np.testing.assert_array_equal(before.scans[0].ranges, ranges)
    assert len(before.scans[0].angles) == 5


def test_bodies_are_the_models_blocks_in_the_robot_frame(tmp_path):
    view = WorldView(lesson_like(tmp_path, TRIANGLE))
    square, triangle = (r.body for r in view.robots())
    assert [r.nose for r in view.robots()] == [True, False]   # gui_nose 1, Stage's default 0
    assert len(square) == 1 and np.ptp(square[0], axis=0).tolist() == [0.4, 0.4]
    (points,) = triangle
    assert points.shape == (3, 2)
    np.testing.assert_allclose(np.ptp(points, axis=0), [0.6, 0.4], atol=1e-9)


def test_without_a_window_block_the_view_holds_the_robots(tmp_path):
    view = WorldView(lesson_like(tmp_path, TRIANGLE))
    camera = view.camera()
    assert camera.size_px == (600, 400)
    assert (camera.center_x, camera.center_y) == (-0.5, 0.0)    # between (1, 2) and (-2, -2)
    # the robots and ROBOTS_MARGIN_M around them: 4 + 2 m tall in 400 px
    assert camera.scale == min(600 / (3 + 2 * ROBOTS_MARGIN_M), 400 / (4 + 2 * ROBOTS_MARGIN_M))
    assert view.options == DrawOptions()


def test_the_window_block_sets_the_view_and_options(tmp_path):
    window = 'window( size [ 300 200 ] center [ 0.5 -1 ] rotate [ 10 -1.5 ] scale 12.5 ' \
             'show_data 0 show_trailfast 1 )\n'
    view = WorldView(lesson_like(tmp_path, window))
    camera = view.camera()
    assert (camera.size_px, camera.center_x, camera.center_y, camera.scale, camera.yaw_deg) == \
        ((300, 200), 0.5, -1.0, 12.5, -1.5)
    assert view.options == DrawOptions(data=False, trails=True)
    assert view.camera(screen_px=(250, 150)).size_px == (250, 150)   # never beyond the screen


def test_the_floor_is_drawn_once_per_view(tmp_path):
    view = WorldView(lesson_like(tmp_path))
    camera = view.camera()
    image = view.floor(camera)
    assert image.size == camera.size_px
    assert view.floor(camera) is image
    assert view.floor(camera.panned(10, 0)) is not image
    assert view.floor(camera, grid_on=False) is not image
