"""Installs the course_common Python package (catkin_python_setup); do not run by hand."""
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=['course_common', 'course_common.rviz',
                                           'course_common.testing'],
                                 package_dir={'': 'src'}))
