# The Python package ragdoll_sim (python/ragdoll_sim) for catkin_python_setup(); the compiled
# module ragdoll_sim._core is built by CMake next to the generated messages.
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=['ragdoll_sim', 'ragdoll_sim.batch'],
    package_dir={'': 'python'},
))
