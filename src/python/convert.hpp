// Python values -> the Scene's types, every refusal a std::invalid_argument (ValueError) that
// names the argument and what it got.
#pragma once

#include <map>
#include <string>

#include <pybind11/pybind11.h>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {
namespace python {

// Any sequence of 3 finite numbers (list, tuple, NumPy array).
Vec3 toVec3(const pybind11::handle& value, const char* argument);
// 4 finite numbers x y z w of non-zero norm, normalised.
Quat toQuat(const pybind11::handle& value, const char* argument);
// position, and orientation (x y z w) or rpy (roll pitch yaw, rad), at most one of the two.
Transform toPose(const pybind11::handle& position, const pybind11::handle& orientation,
                 const pybind11::handle& rpy);
// A dict name -> number.
std::map<std::string, double> toNumberMap(const pybind11::handle& value, const char* argument);

}  // namespace python
}  // namespace ragdoll_sim
