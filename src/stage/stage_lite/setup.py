"""Installs the stage_lite Python package (catkin_python_setup); do not run by hand."""
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(
    packages=['stage_lite', 'stage_lite.model', 'stage_lite.node', 'stage_lite.view',
              'stage_lite.controllers', 'stage_lite.testing'],
    package_dir={'': 'src'}))
