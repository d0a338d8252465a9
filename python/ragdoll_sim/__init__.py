"""ragdoll_sim's Python API: the ROS-free Scene (compiled module ragdoll_sim._core).

    import ragdoll_sim
    scene = ragdoll_sim.Scene(dt=0.001)

The ROS message and service classes stay where catkin generates them (ragdoll_sim.msg,
ragdoll_sim.srv). See docs/python.md.
"""
from ._core import *  # noqa: F401,F403  (the compiled module's classes and functions)
