"""The camera model against the real stageros's cameras (test/golden/camera/): the interface
equal; depth and colour per pixel, frame by frame (figures in test/golden/camera/README.md)."""
import math
import os

import numpy as np
import pytest
from stage_lite.model.world import load_world
from stage_lite.node import camera_wire
from stage_lite.node.camera_names import camera_names

HERE = os.path.dirname(os.path.abspath(__file__))
GOLDEN = os.path.join(HERE, '..', 'golden', 'camera')
WORLDS = os.path.join(HERE, '..', 'worlds')
#: (golden file, world, sim steps to its stamp (nothing moves), robot, its k-th camera)
FRAMES = [
    ('node_camera_robot0.npz', 'node_camera.world', 16, 0, 0),       # level, square to a wall
    ('node_camera_robot1_cam0.npz', 'node_camera.world', 10, 1, 0),  # Stage's default fov
    ('node_camera_robot1_cam1.npz', 'node_camera.world', 22, 1, 1),  # panned 90 deg
    ('camera_golden_robot0.npz', 'camera_golden.world', 10, 0, 0),   # panned, tilted down
    ('camera_golden_robot2.npz', 'camera_golden.world', 38, 2, 0),   # tilted up, a robot
    ('camera_golden_robot3.npz', 'camera_golden.world', 76, 3, 0),   # tilted 25 deg down
]
#: The bounds asked for; every frame measures 1.0 for both (README there).
MIN_DEPTH_SHARE = 0.98
MIN_COLOUR_SHARE = 0.95
DEPTH_REL = 0.01
COLOUR_LEVELS = 8
#: What every frame measures: each pixel's depth within this (float32 of a 24-bit depth
#: buffer's value through realDistance), each colour exact.
ALL_PIXELS_DEPTH_REL = 1e-4

_worlds = {}


def _frame(name, world, steps, robot, k):
    key = (world, steps)
    if key not in _worlds:
        w = load_world(os.path.join(WORLDS, world))
        for _ in range(steps):
            w.step()
        _worlds[key] = w
    w = _worlds[key]
    return np.load(os.path.join(GOLDEN, name)), w.cameras.by_robot[robot][k], w


@pytest.fixture(params=FRAMES, ids=[f[0][:-4] for f in FRAMES])
def pair(request):
    name, world, steps, robot, k = request.param
    real, v, w = _frame(name, world, steps, robot, k)
    return real, v, w, robot, k


def depth_close(real, v, rel):
    """Per pixel: stageros's depth within rel of the real one's, or infinite in both."""
    mine = camera_wire.stageros_depth(v.depth, v.near, v.far)
    rd = real['depth']
    same_inf = np.isinf(rd) & (mine == rd)
    finite = np.isfinite(rd) & np.isfinite(mine)
    close = np.zeros(rd.shape, bool)
    close[finite] = np.abs(mine[finite] - rd[finite]) <= rel * np.abs(rd[finite])
    return same_inf | close


def colour_diff(real, v):
    return np.abs(v.rgba.astype(int) - real['rgba'].astype(int)).max(axis=2)


def test_interface(pair):
    real, v, w, robot, k = pair
    n_cameras = len(w.cameras.by_robot[robot])
    names = camera_names(robot, w.robots[robot].model_name, len(w.robots), n_cameras)[k]
    assert list(real['image_fields']) == [camera_wire.RGBA8, names.frame, str(4 * v.width), '0']
    assert list(real['depth_fields']) == [camera_wire.DEPTH_32F, names.frame, str(4 * v.width),
                                          '0']
    assert str(real['info_frame']) == names.frame
    assert tuple(real['info_size']) == (v.width, v.height)
    fx, fy, cx, cy = v.intrinsics()
    assert list(real['K']) == pytest.approx([fx, 0, cx, 0, fy, cy, 0, 0, 1], rel=1e-12)
    assert list(real['P']) == pytest.approx([fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0],
                                            rel=1e-12)
    assert list(real['R']) == [1, 0, 0, 0, 1, 0, 0, 0, 1]
    assert list(real['D']) == [0.0] * 4 and str(real['distortion_model']) == ''
    assert real['rgba'].shape == v.rgba.shape and real['depth'].shape == v.depth.shape


def test_depth_per_pixel(pair):
    real, v, _, _, _ = pair
    share = np.mean(depth_close(real, v, DEPTH_REL))
    assert share >= MIN_DEPTH_SHARE, share


def test_colour_per_pixel(pair):
    real, v, _, _, _ = pair
    share = np.mean(colour_diff(real, v) <= COLOUR_LEVELS)
    assert share >= MIN_COLOUR_SHARE, share


def test_every_pixel_agrees(pair):
    real, v, _, _, _ = pair
    assert depth_close(real, v, ALL_PIXELS_DEPTH_REL).all()
    assert (colour_diff(real, v) == 0).all()


def test_frames_see_what_they_were_posed_for():
    """The frames hold what they were captured for (so a frame of nothing cannot pass)."""
    real, _, _ = _frame(*FRAMES[0])
    assert math.isclose(float(real['depth'][12, 16]), 1.95, rel_tol=1e-6)
    real, _, _ = _frame(*FRAMES[4])      # robot_2 sees robot_0 (red) and the box (yellow)
    colours = {tuple(c) for c in real['rgba'][..., :3].reshape(-1, 3).tolist()}
    assert {(255, 0, 0), (255, 255, 0)} <= colours
    real, _, _ = _frame(*FRAMES[3])      # robot_0 sees robot_1 (green) and the box
    colours = {tuple(c) for c in real['rgba'][..., :3].reshape(-1, 3).tolist()}
    assert {(0, 255, 0), (255, 255, 0), (0, 0, 255), (77, 77, 77)} <= colours
