"""Installs the swarm Python package (catkin_python_setup); do not run by hand."""
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=['swarm'], package_dir={'': 'src'}))
