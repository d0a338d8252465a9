// ragdoll_sim._core: the Scene's Python API (docs/python.md); python/ragdoll_sim re-exports it.
#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "ragdoll_sim's ROS-free Scene: load worlds and models, push, step, read reports.";
  ragdoll_sim::python::bindScene(m);
  ragdoll_sim::python::bindFall(m);
}
