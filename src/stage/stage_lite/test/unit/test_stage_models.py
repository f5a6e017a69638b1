"""Stage's model bodies (stage_lite.model.models and .bodies): default sizes, CalcSize,
boundary, block( ) shapes, stacking, and the geometry stageros publishes."""
import math

import numpy as np
import pytest
from stage_lite.model.bodies import Block, calc_size, canonical_winding
from stage_lite.model.world import load_world


def world(tmp_path, text):
    p = tmp_path / 'w.world'
    p.write_text('resolution 0.02\n' + text)
    return load_world(str(p))


def by_name(w, name):
    return next(m for m in w.models if m.name == name)


def test_defaults_a_unit_square_scaled_to_stages_default_size(tmp_path):
    w = world(tmp_path, 'model( name "m" )\nposition( name "p" )\nranger( name "r" )')
    m, p, r = by_name(w, 'm'), by_name(w, 'p'), by_name(w, 'r')
    assert m.geom_size == (0.4, 0.4, 1.0) and p.geom_size == (0.4, 0.4, 1.0)
    assert m.blocks[0].pts.tolist() == [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]]
    assert (m.blocks[0].zmin, m.blocks[0].zmax) == (0.0, 1.0)
    assert r.geom_size == (0.15, 0.15, 0.2) and r.blocks == []   # a ranger has no body
    assert m.color == (1.0, 0.0, 0.0, 1.0)


def test_calc_size_scales_every_block_to_the_size_z_from_zero():
    blocks = [Block([(0, 0), (2, 0), (2, 1)], 0.5, 1.0), Block([(2, 1), (4, 1), (4, 3)], 0.6, 0.8)]
    calc_size(blocks, (1.0, 0.6, 0.25))
    assert blocks[0].pts.ravel().tolist() == pytest.approx([-0.5, -0.3, 0.0, -0.3, 0.0, -0.1],
                                                           abs=1e-12)
    # z is scaled by size.z / (zmax - zmin) but not shifted: [0.5, 1.0] becomes [0.25, 0.5]
    assert (blocks[0].zmin, blocks[0].zmax) == (0.25, 0.5)


def test_block_bodies_fill_the_models_size(tmp_path):
    w = world(tmp_path, 'model( name "ell" size [0.8 0.6 0.5] block( points 3 point[0] [0 0]'
                        ' point[1] [0 2] point[2] [4 0] z [0 1] ) )')
    ell = by_name(w, 'ell')
    (b,) = ell.blocks
    # clockwise as written: Stage reverses it to counter-clockwise
    assert b.pts.tolist() == [[0.4, -0.3], [-0.4, 0.3], [-0.4, -0.3]]
    assert (b.zmin, b.zmax) == (0.0, 0.5)


def test_canonical_winding():
    ccw = [(0, 0), (1, 0), (1, 1)]
    assert canonical_winding(ccw) == ccw
    assert canonical_winding(ccw[::-1]) == ccw


def test_boundary_adds_four_thin_walls_on_the_bodys_box(tmp_path):
    w = world(tmp_path, 'model( name "pen" size [4 2 0.5] boundary 1 )')
    pen = by_name(w, 'pen')
    assert len(pen.blocks) == 5
    walls = sorted(np.ptp(b.pts, axis=0).round(9).tolist() for b in pen.blocks[1:])
    assert walls == [[0.01, 2.0], [0.01, 2.0], [4.0, 0.01], [4.0, 0.01]]


def test_children_stand_on_their_parent(tmp_path):
    w = world(tmp_path, 'position( name "p" pose [1 2 0 90] size [0.5 0.5 0.3]'
                        ' model( name "c" pose [0.2 0 0.1 0] size [0.1 0.1 0.1] ) )')
    c = by_name(w, 'c')
    x, y, z, a = c.global_pose()
    assert (x, y, z) == pytest.approx((1.0, 2.2, 0.4), abs=1e-12) and a == math.pi / 2
    assert c.block_z(c.blocks[0]) == pytest.approx((0.4, 0.5), abs=1e-12)


def test_laser_pose_as_stageros_publishes_it(tmp_path):
    w = world(tmp_path, 'position( size [0.35 0.35 0.25] ranger( pose [0.05 0 0.02 0]'
                        ' sensor( range [0 30] fov 270.25 samples 1081 ) ) )')
    g = w.robots[0].rangers[0]
    assert g.pose == (0.05, 0.0, 0.27, 0.0)      # z: the body's height plus the ranger's z
    assert (g.samples, g.range_min, g.range_max) == (1081, 0.0, 30.0)
    assert g.angle_min == pytest.approx(-2.35838, abs=1e-5)
    assert g.angle_increment == pytest.approx(0.00436736, abs=1e-8)
    # the beam: the ranger's z (0.25 + 0.02) plus half the transducer's default 0.02
    assert g.beam_z == pytest.approx(0.28, abs=1e-12)


def test_a_one_beam_ranger_publishes_stageros_division(tmp_path):
    w = world(tmp_path, 'position( ranger( sensor( samples 1 ) ) )')
    assert w.robots[0].rangers[0].angle_increment == math.inf


def test_names_and_colours(tmp_path):
    w = world(tmp_path, 'position( name "a" color "gray30" )\nposition( color_rgba [0 1 0 1] )')
    a, b = w.robots
    assert (a.model_name, b.model_name) == ('a', '')
    assert a.color_rgb == pytest.approx((77 / 255,) * 3) and b.color_rgb == (0.0, 1.0, 0.0)
