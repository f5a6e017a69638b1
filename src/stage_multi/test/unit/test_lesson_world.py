"""The lesson's world folder: the floor plan's script reproduces the committed office.pgm.

How Stage runs this world (its figures, the drive into the wall, real Stage's capture of it
step by step) is tested in stage_lite, from the capture with this world embedded
(stage_lite/test/golden/data/lesson_drive.npz); through ROS, by this package's rostests."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WORLD_DIR = os.path.join(HERE, '..', '..', 'world')


def test_floor_plan_script_reproduces_the_committed_pgm(tmp_path):
    out = tmp_path / 'office.pgm'
    subprocess.run([sys.executable, os.path.join(WORLD_DIR, 'draw_office.py'), str(out)],
                   check=True, capture_output=True)
    with open(os.path.join(WORLD_DIR, 'office.pgm'), 'rb') as f:
        assert out.read_bytes() == f.read()
