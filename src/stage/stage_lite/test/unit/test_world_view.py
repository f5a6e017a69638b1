"""stage_lite.node.world_view: the trails and robot views the window and ~save_image draw from."""
import numpy as np
from stage_lite.model.world import load_world
from stage_lite.node.world_view import WorldView
from stage_lite.testing.room import write_room_pgm

WORLD = '''resolution 0.02
interval_sim 100
model( size [10 10 1] bitmap "room.pgm" pose [0 0 0 0] )
position( pose [0 0 0 0] size [0.4 0.4 0.25] color "blue"
  ranger( sensor( range [0 20] fov 180 samples 5 ) ) )
'''


def lesson_like(tmp_path):
    write_room_pgm(str(tmp_path / 'room.pgm'))
    (tmp_path / 'w.world').write_text(WORLD)
    return load_world(str(tmp_path / 'w.world'))


def test_trails_follow_the_steps_and_reset_clears_them(tmp_path):
    world = lesson_like(tmp_path)
    view = WorldView(world)
    world.set_command(0, 1.0, 0.0, 0.0)
    for _ in range(5):
        world.step()
        view.record()
    (robot,) = view.robots()
    np.testing.assert_allclose(robot.trail[:, 0], [0.1, 0.2, 0.3, 0.4, 0.5], atol=1e-9)
    assert robot.pose[:2] == world.robots[0].pose[:2] and robot.color == (0.0, 0.0, 1.0)
    world.reset()
    view.clear()
    assert len(view.robots()[0].trail) == 0


def test_views_are_copies_taken_now(tmp_path):
    world = lesson_like(tmp_path)
    view = WorldView(world)
    world.step()
    (before,) = view.robots()
    ranges = before.rangers[0].ranges.copy()
    world.robots[0].rangers[0].ranges[:] = 0.0    # the next step writes over the scan
    np.testing.assert_array_equal(before.rangers[0].ranges, ranges)
    assert len(before.rangers[0].angles) == 5


def test_the_floor_is_fitted_once_per_size(tmp_path):
    view = WorldView(lesson_like(tmp_path))
    fitted, image = view.floor(200, 100)
    assert image.size[0] <= 200 and image.size[1] <= 100
    assert view.floor(200, 100)[1] is image
    assert view.floor(300, 300)[1] is not image
