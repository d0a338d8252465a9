"""ragdoll_sim's Python API: the ROS-free Scene (compiled module ragdoll_sim._core).

    import ragdoll_sim
    scene = ragdoll_sim.Scene(dt=0.001)

The ROS message and service classes stay where catkin generates them (ragdoll_sim.msg,
ragdoll_sim.srv). See docs/python.md.
"""
# Imported from the source folder first (catkin's devel __init__ puts it at the head of sys.path,
# and spawned processes such as Dask's local workers inherit that order), the package must still
# find _core in the devel folder: extend_path adds every ragdoll_sim folder on sys.path.
__path__ = __import__("pkgutil").extend_path(__path__, __name__)

from ._core import *  # noqa: F401,F403,E402  (the compiled module's classes and functions)
