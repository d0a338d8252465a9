#include "convert.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace py = pybind11;

namespace ragdoll_sim {
namespace python {

namespace {

std::vector<double> numbers(const py::handle& value, const char* argument, size_t n) {
  std::vector<double> out;
  try {
    for (const py::handle item : py::iter(value)) out.push_back(item.cast<double>());
  } catch (const py::error_already_set&) {
    throw std::invalid_argument(std::string(argument) + " must be a sequence of " +
                                std::to_string(n) + " numbers, got " +
                                std::string(py::str(py::repr(value))));
  } catch (const py::cast_error&) {
    throw std::invalid_argument(std::string(argument) + " must be a sequence of " +
                                std::to_string(n) + " numbers, got " +
                                std::string(py::str(py::repr(value))));
  }
  if (out.size() != n)
    throw std::invalid_argument(std::string(argument) + " must have " + std::to_string(n) +
                                " numbers, got " + std::to_string(out.size()));
  for (double x : out)
    if (!std::isfinite(x))
      throw std::invalid_argument(std::string(argument) + " must be finite, got " +
                                  std::string(py::str(py::repr(value))));
  return out;
}

}  // namespace

Vec3 toVec3(const py::handle& value, const char* argument) {
  const std::vector<double> v = numbers(value, argument, 3);
  return Vec3(v[0], v[1], v[2]);
}

Quat toQuat(const py::handle& value, const char* argument) {
  const std::vector<double> v = numbers(value, argument, 4);
  const Quat q(v[3], v[0], v[1], v[2]);
  if (!(q.norm() > 1e-9))
    throw std::invalid_argument(std::string(argument) +
                                " (x, y, z, w) has norm 0: it is no rotation");
  return q.normalized();
}

Transform toPose(const py::handle& position, const py::handle& orientation,
                 const py::handle& rpy) {
  Transform pose;
  pose.p = toVec3(position, "position");
  if (!orientation.is_none() && !rpy.is_none())
    throw std::invalid_argument("give orientation (a quaternion) or rpy, not both");
  if (!orientation.is_none()) pose.q = toQuat(orientation, "orientation");
  if (!rpy.is_none()) {
    const Vec3 a = toVec3(rpy, "rpy");
    pose.q = quatFromRpy(a.x(), a.y(), a.z());
  }
  return pose;
}

std::map<std::string, double> toNumberMap(const py::handle& value, const char* argument) {
  if (!py::isinstance<py::dict>(value))
    throw std::invalid_argument(std::string(argument) + " must be a dict name -> number, got " +
                                std::string(py::str(py::repr(value))));
  std::map<std::string, double> out;
  for (const auto& item : py::reinterpret_borrow<py::dict>(value)) {
    try {
      out[item.first.cast<std::string>()] = item.second.cast<double>();
    } catch (const py::cast_error&) {
      throw std::invalid_argument(std::string(argument) + ": entry " +
                                  std::string(py::str(py::repr(item.first))) +
                                  " must map a name to a number");
    }
  }
  return out;
}

}  // namespace python
}  // namespace ragdoll_sim
