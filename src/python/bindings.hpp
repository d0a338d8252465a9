// The parts of the compiled module ragdoll_sim._core, one concern per bind_*.cpp; module.cpp
// calls each. The bindings only convert: every rule and all physics stay in the Scene.
#pragma once

#include <pybind11/pybind11.h>

namespace ragdoll_sim {
namespace python {

// A docstring written as R"doc(\n...\n)doc" without its first newline (the literal stays
// alive: pybind11 keeps the pointer).
inline const char* pydoc(const char* text) { return text[0] == '\n' ? text + 1 : text; }

void bindScene(pybind11::module_& m);    // bind_scene.cpp: Scene, Model, InjuryReport
void bindFall(pybind11::module_& m);     // bind_fall.cpp: the fall recorder (ragdoll_sim.batch)

}  // namespace python
}  // namespace ragdoll_sim
