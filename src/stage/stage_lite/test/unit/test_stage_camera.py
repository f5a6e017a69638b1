"""Stage's camera (stage_lite.model.camera, camera_render): properties and defaults, where it
looks from, depth and colour of its frames on small worlds of known geometry, update times,
and the values Stage makes no frame of.

Stage's depth is the z-buffer made linear (PerspectiveCamera::realDistance): the distance
along the view axis, so a wall square to the view at d reads d in every pixel; the range
along a pixel's own ray is that over the cosine of the ray's angle to the axis. A pixel is
what its sample point sees (SAMPLE_X, SAMPLE_Y from its top-left corner, not its centre), and
a surface's window depth is pushed back by its polygon offset (factor x its depth slope per
pixel: 2 for the floor, 0.5 for blocks)."""
import math

import numpy as np
import pytest
from stage_lite.model.camera_render import (
    BLOCK_OFFSET_FACTOR,
    CLEAR_RGBA,
    FLOOR_OFFSET_FACTOR,
    FLOOR_RGBA,
    SAMPLE_X,
    SAMPLE_Y,
    gl_rgba,
)
from stage_lite.model.world import load_world

DEPTH_TOL = 1e-6      # the ray cast in float64, stored as float32 (Stage's): relative
WALL = '''resolution 0.02
model( name "wall" pose [ %(d)s 0 0 0 ] size [ 0.2 6 %(h)s ] color "blue" )
position( name "r0" pose [ 0 0 0 0 ] size [ 0.3 0.3 0.2 ] color "red"
  camera( %(cam)s )
)
'''


def world(tmp_path, d=3.1, h=1.0, cam='resolution [ 32 24 ] fov [ 60 40 ]', text=None):
    """A blue wall whose near face is at d - 0.1 m ahead of a robot carrying the camera (its
    eye 0.2 m above the floor)."""
    p = tmp_path / 'cam.world'
    p.write_text(text if text is not None else WALL % dict(d=d, h=h, cam=cam))
    return load_world(str(p))


def frame(w, steps=1):
    for _ in range(steps):
        w.step()
    return w.cameras.views[0]


def pixel_tangents(v):
    """The tangents of each column's and row's sample point's angle to the view axis (row 0
    the top)."""
    u = ((np.arange(v.width) + SAMPLE_X) * 2.0 / v.width - 1.0) * math.tan(
        math.radians(v.hfov_deg / 2))
    t = (1.0 - (np.arange(v.height) + SAMPLE_Y) * 2.0 / v.height) * math.tan(
        math.radians(v.vfov_deg / 2))
    return u, t


def window_depth(t, near=0.2, far=8.0):
    """The GL window depth of planar depth t (glFrustum's), and back (realDistance)."""
    return far / (far - near) * (1 - near / t)


def real_distance(w, near=0.2, far=8.0):
    return near * far / (far - w * (far - near))


def test_stage_defaults(tmp_path):
    w = world(tmp_path, cam='')
    m = w.cameras.views[0].model
    assert (m.resolution, m.range, m.fov_deg, m.pantilt_deg) == \
        ((32, 32), (0.2, 8.0), (70.0, 40.0), (0.0, 0.0))
    assert (m.geom_size, m.color, m.interval_us) == ((0.1, 0.07, 0.05), (0.0, 0.0, 0.0, 1.0),
                                                     100000)
    assert m.eye()[:3] == (0.0, 0.0, 0.2)      # the parent's x, y at the camera's base


def test_properties_are_read(tmp_path):
    w = world(tmp_path, cam='resolution [ 16 8 ] range [ 0.5 4 ] fov [ 90 45 ] pantilt [ 10 5 ]'
              ' pose [ 0.1 0 0.05 0 ]')
    v = w.cameras.views[0]
    m = v.model
    assert (v.width, v.height, v.near, v.far, v.hfov_deg, v.vfov_deg) == (16, 8, 0.5, 4.0,
                                                                          90.0, 45.0)
    assert m.pantilt_deg == (10.0, 5.0)
    assert m.eye()[:3] == (0.0, 0.0, pytest.approx(0.25))   # x, y: the parent's, not its own
    assert v.tf_xyz == (0.1, 0.0, pytest.approx(0.25))     # stageros's tf: its own pose


def test_no_frame_before_the_first_update(tmp_path):
    w = world(tmp_path)
    assert not w.cameras.views[0].has_data
    assert frame(w).has_data


def test_wall_depth_is_the_distance_along_the_axis(tmp_path):
    v = frame(world(tmp_path, d=3.1, h=1.0))
    u, t = pixel_tangents(v)
    on_wall = (0.2 + 3.0 * t >= 0.0) & (0.2 + 3.0 * t <= 1.0)
    assert on_wall.any() and not on_wall.all()
    assert np.allclose(v.depth[on_wall], 3.0, rtol=DEPTH_TOL)
    # the range along each pixel's ray: distance / cos of its angle to the axis
    rng = v.depth[on_wall] * np.sqrt(1 + u[None, :] ** 2 + t[on_wall, None] ** 2)
    cos = 1 / np.sqrt(1 + u[None, :] ** 2 + t[on_wall, None] ** 2)
    assert np.allclose(rng, 3.0 / cos, rtol=DEPTH_TOL)


def test_above_the_wall_reads_far_below_it_the_floor(tmp_path):
    v = frame(world(tmp_path, d=3.1, h=0.5))
    _, t = pixel_tangents(v)
    above = 0.2 + 3.0 * t > 0.5
    assert above.any()
    # nothing drawn within far: realDistance(1.0) = far (stageros sends +inf)
    assert (v.depth[above] == np.float32(8.0)).all()
    below = 0.2 + 3.0 * t < 0.0
    assert below.any()
    floor_t = -0.2 / t[below]            # where each row's ray meets z = 0
    # the floor's polygon offset: its window depth pushed back by a constant, the factor x
    # its slope per row: scale near x d(1/t) per row = the tangent per row over the eye's
    # height
    slope = 8.0 / 7.8 * 0.2 * (2 * math.tan(math.radians(20)) / 24) / 0.2
    push = FLOOR_OFFSET_FACTOR * slope
    dwin = window_depth(floor_t) + push
    drawn = dwin < 1.0       # pushed to 1.0 or beyond, it fails the depth test: not drawn
    assert drawn.any()
    want = real_distance(dwin[drawn])
    assert np.allclose(v.depth[below][drawn], want[:, None], rtol=DEPTH_TOL)
    assert (v.depth[below][~drawn] == np.float32(8.0)).all()
    assert not np.isinf(v.depth).any()   # Stage's own depth: far, not inf (stageros's)


def test_colours(tmp_path):
    v = frame(world(tmp_path, d=3.1, h=0.5))
    _, t = pixel_tangents(v)
    rows = {'sky': 0.2 + 3.0 * t > 0.5, 'wall': (0.2 + 3.0 * t >= 0) & (0.2 + 3.0 * t <= 0.5),
            'floor': 0.2 + 3.0 * t < -1.0}   # near rows: their offset floor is drawn
    want = {'sky': gl_rgba(CLEAR_RGBA), 'wall': (0, 0, 255, 255),
            'floor': gl_rgba(FLOOR_RGBA)}
    for name, mask in rows.items():
        assert (v.rgba[mask] == want[name]).all(), name
    assert gl_rgba(FLOOR_RGBA) == (255, 255, 255, 255)
    assert gl_rgba(CLEAR_RGBA) == (178, 178, 204, 255)     # as read back from real Stage


def test_beyond_far_is_not_drawn(tmp_path):
    v = frame(world(tmp_path, d=9.1, cam='resolution [ 8 8 ] fov [ 20 10 ]'))
    # the upper rows (above the horizon: the floor is seen below it)
    assert (v.depth[:4] == np.float32(8.0)).all()
    assert (v.rgba[:4] == gl_rgba(CLEAR_RGBA)).all()


def test_what_is_nearer_than_near_is_clipped(tmp_path):
    text = WALL % dict(d=3.1, h=1.0, cam='resolution [ 8 8 ] fov [ 20 10 ] range [ 0.5 8 ]')
    text += 'model( pose [ 0.35 0 0 0 ] size [ 0.1 1 1 ] color "green" )\n'
    v = frame(world(tmp_path, text=text))
    # the upper rows: the wall behind the clipped box
    assert np.allclose(v.depth[:4], 3.0, rtol=DEPTH_TOL)
    text = text.replace('range [ 0.5 8 ]', 'range [ 0.2 8 ]')
    v = frame(world(tmp_path, text=text))
    assert np.allclose(v.depth[:4], 0.3, rtol=DEPTH_TOL)


@pytest.mark.parametrize('pantilt, sees', [('[ 90 0 ]', 'right'), ('[ -90 0 ]', 'left')])
def test_pan_turns_right(tmp_path, pantilt, sees):
    text = ('resolution 0.02\nmodel( pose [ 0 -2.1 0 0 ] size [ 6 0.2 1 ] color "green" )\n'
            'position( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.2 ]'
            ' camera( resolution [ 8 8 ] fov [ 20 10 ] pantilt %s ) )\n' % pantilt)
    v = frame(world(tmp_path, text=text))
    if sees == 'right':
        assert np.allclose(v.depth, 2.0, rtol=DEPTH_TOL)
    else:      # the upper rows: nothing; the floor below the horizon
        assert (v.depth[:4] == np.float32(8.0)).all()


def test_tilt_looks_down(tmp_path):
    text = ('resolution 0.02\nposition( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.5 ]'
            ' camera( resolution [ 1 1 ] fov [ 10 10 ] pantilt [ 0 30 ] ) )\n')
    v = frame(world(tmp_path, text=text))
    # the axis meets the floor 0.5 / sin 30 away along it; its polygon offset reads deeper
    assert v.depth[0, 0] > 0.5 / math.sin(math.radians(30))
    assert tuple(v.rgba[0, 0]) == gl_rgba(FLOOR_RGBA)


def test_a_box_top_seen_from_above(tmp_path):
    text = ('resolution 0.02\nmodel( pose [ 1 0 0 0 ] size [ 1 1 0.2 ] color "yellow" )\n'
            'position( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.5 ]'
            ' camera( resolution [ 1 1 ] fov [ 10 10 ] pantilt [ 0 30 ] ) )\n')
    v = frame(world(tmp_path, text=text))
    # the one pixel's sample point, 30 deg down; the eye 0.3 m above the top, whose normal
    # seen from the eye is (0, sin 60, cos 60): its 1 / t rises by sin 60 / 0.3 per tangent
    tan5 = math.tan(math.radians(5))
    vt = (1 - 2 * SAMPLE_Y) * tan5
    t = 0.3 / (0.5 - math.sin(math.radians(60)) * vt)
    slope = 8.0 / 7.8 * 0.2 * math.sin(math.radians(60)) / 0.3 * 2 * tan5
    want = real_distance(window_depth(t) + BLOCK_OFFSET_FACTOR * slope)
    assert v.depth[0, 0] == pytest.approx(want, rel=DEPTH_TOL)
    assert want > t
    assert tuple(v.rgba[0, 0]) == (255, 255, 0, 255)


@pytest.mark.parametrize('axis', ['row', 'column'])
def test_a_pixel_is_what_its_sample_point_sees(tmp_path, axis):
    """An edge between a pixel's sample point and its centre: the pixel takes the sample
    point's side (the wall's top edge at row 5.3, its right end at column 20.45)."""
    tan20, tan30 = math.tan(math.radians(20)), math.tan(math.radians(30))
    h = 0.2 + 3.0 * (1 - 5.3 / 12) * tan20 if axis == 'row' else 1.0
    end = -3.0 * (20.45 * 2 / 32 - 1) * tan30 if axis == 'column' else -3.0
    text = ('resolution 0.02\nmodel( pose [ 3.1 %r 0 0 ] size [ 0.2 6 %r ] color "blue" )\n'
            'position( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.2 ] color "red"'
            ' camera( resolution [ 32 24 ] fov [ 60 40 ] ) )\n' % (end + 3.0, h))
    v = frame(world(tmp_path, text=text))
    wall = np.isclose(v.depth, 3.0, rtol=DEPTH_TOL)
    if axis == 'row':
        assert not wall[5].any() and wall[6].all()      # the centre 5.5 lies on the wall
    else:
        assert wall[6:12, 20].all() and not wall[6:12, 21].any()   # the centre 20.5: beyond


def test_an_oblique_face_reads_deeper_by_its_offset(tmp_path):
    """A wall at 45 deg to the view: its depth pushed back by 0.5 x its slope per column."""
    text = ('resolution 0.02\nmodel( pose [ 3 0 0 45 ] size [ 0.1 4 1.0 ] color "blue" )\n'
            'position( pose [ 0 0 0 0 ] size [ 0.3 0.3 0.2 ]'
            ' camera( resolution [ 16 8 ] fov [ 40 20 ] ) )\n')
    v = frame(world(tmp_path, text=text))
    u, _ = pixel_tangents(v)
    # the face toward the eye: x + y = 3 - 0.05 sqrt 2 (its normal (1, 1) / sqrt 2); along
    # the axis (+x) with lateral tangent u (to the right: -y), x = t and y = -u t
    c = 3 - 0.05 * math.sqrt(2)
    t = c / (1 - u)
    w = window_depth(t)
    slope = np.abs(np.diff(w)).max()     # its window depth is affine in the column
    assert np.allclose(np.diff(np.diff(1 / t)), 0, atol=1e-12)
    want = real_distance(w + BLOCK_OFFSET_FACTOR * slope)
    on = v.depth[4] < 8.0                 # the right-most columns pass the wall's end
    assert on.sum() >= 12
    assert np.allclose(v.depth[4][on], want[on], rtol=DEPTH_TOL)
    assert (want > t).all() and not np.allclose(want, t, rtol=1e-3)


def test_the_view_follows_the_robot(tmp_path):
    w = world(tmp_path, d=3.1, cam='resolution [ 4 4 ] fov [ 10 10 ]')
    w.set_command(0, 1.0, 0.0, 0.0)
    assert frame(w, 1).depth[1, 1] == pytest.approx(3.0)   # drawn before the step's move
    assert frame(w, 1).depth[1, 1] == pytest.approx(2.9)


def test_update_chains(tmp_path):
    """The constructor's chain (100 ms, then every update_interval) and Subscribe's (every
    update_interval): frames at both."""
    w = world(tmp_path, cam='resolution [ 2 2 ] update_interval 300')
    v = w.cameras.views[0]
    times = []
    for _ in range(10):
        v.has_data = False
        w.step()
        if v.has_data:
            times.append(w.sim_time_us // 1000)
    assert times == [100, 300, 400, 600, 700, 900, 1000]


@pytest.mark.parametrize('res, stage', [('[ 0 32 ]', 'makes no frame'),
                                        ('[ -4 32 ]', 'crashes allocating its frame')])
def test_no_pixels_one_warning_naming_the_line_and_the_world_runs(tmp_path, res, stage):
    text = WALL % dict(d=3.1, h=1.0, cam='\n    resolution %s' % res)
    w = world(tmp_path, text=text)
    lines = [m for m in w.warnings if 'camera' in m]
    assert len(lines) == 1 and lines[0].startswith('%s:5: ' % (tmp_path / 'cam.world'))
    assert stage in lines[0] and 'not published' in lines[0]
    assert w.cameras.views == [] and w.cameras.by_robot == [[]]
    w.set_command(0, 0.5, 0.0, 0.0)
    for _ in range(3):
        w.step()
    assert w.robots[0].pose[0] == pytest.approx(0.15)


@pytest.mark.parametrize('prop, what', [('fov [ 0 40 ]', 'fov [0 40]'),
                                        ('fov [ 60 180 ]', 'fov [60 180]'),
                                        ('range [ 0 8 ]', 'range [0 8]'),
                                        ('range [ 3 2 ]', 'range [3 2]')])
def test_bad_fov_or_range_warns(tmp_path, prop, what):
    w = world(tmp_path, cam=prop)
    assert any(what in m and 'not published' in m for m in w.warnings), w.warnings
    assert w.cameras.views == []


def test_a_resolution_larger_than_stages_canvas_is_cut(tmp_path):
    w = world(tmp_path, cam='resolution [ 800 600 ]')
    v = w.cameras.views[0]
    assert (v.width, v.height) == (600, 370)     # stageros's 600 x 400 window less the menu
    assert any('Stage cuts it to [600 370]' in m for m in w.warnings)
    text = 'window( size [ 1000 800 ] )\n' + WALL % dict(d=3.1, h=1.0,
                                                          cam='resolution [ 800 600 ]')
    v = world(tmp_path, text=text).cameras.views[0]
    assert (v.width, v.height) == (800, 600)


def test_intrinsics_and_tf(tmp_path):
    v = world(tmp_path, cam='resolution [ 64 48 ] fov [ 90 60 ] pantilt [ 10 20 ]'
              ' pose [ 0.1 0.0 0.0 30 ]').cameras.views[0]
    fx, fy, cx, cy = v.intrinsics()
    assert (fx, fy, cx, cy) == pytest.approx((32.0, 24 / math.tan(math.radians(30)), 32, 24))
    roll, pitch, yaw = v.tf_rpy(0.0)
    assert roll == pytest.approx(math.radians(70) - math.pi)
    assert pitch == 0.0
    assert yaw == pytest.approx(math.radians(30 - 90 - 10))
