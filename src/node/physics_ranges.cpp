#include "physics_ranges.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include <dynamic_reconfigure/Config.h>

#include "pacing.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

using Config = ragdoll_sim::PhysicsConfig;

// Every number of a configuration by its .cfg name (ints as doubles).
std::map<std::string, double> numbers(const Config& c) {
  dynamic_reconfigure::Config m;
  c.__toMessage__(m);
  std::map<std::string, double> out;
  for (const auto& d : m.doubles) out[d.name] = d.value;
  for (const auto& i : m.ints) out[i.name] = i.value;
  return out;
}

std::string interval(double lo, double hi) {
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

}  // namespace

std::string physicsRangeRule(const std::string& field) {
  const std::map<std::string, double> lo = numbers(Config::__getMin__());
  const std::map<std::string, double> hi = numbers(Config::__getMax__());
  const auto l = lo.find(field), h = hi.find(field);
  if (l == lo.end() || h == hi.end()) return "";
  if (field == "real_time_factor") {
    std::ostringstream s;
    s << "0 (as fast as possible) or " << interval(scene::kMinRealTimeFactor, h->second);
    return s.str();
  }
  return interval(l->second, h->second);
}

RangeProblem physicsRangeProblem(const Config& c, const Config* in_force) {
  const std::map<std::string, double> lo = numbers(Config::__getMin__());
  const std::map<std::string, double> hi = numbers(Config::__getMax__());
  const std::map<std::string, double> kept =
      in_force ? numbers(*in_force) : std::map<std::string, double>();
  for (const auto& [field, v] : numbers(c)) {
    const auto k = kept.find(field);
    if (k != kept.end() && k->second == v) continue;
    const double l = lo.at(field), h = hi.at(field);
    bool in = v >= l && v <= h;  // false for NaN
    if (field == "real_time_factor")  // the scene's rule (0 or inf, else >= min) under the max
      in = !*scene::realTimeFactorError(v) && (v == 0.0 || std::isinf(v) || v <= h);
    if (!in) return RangeProblem{field, v, physicsRangeRule(field)};
  }
  return RangeProblem{};
}

PhysicsConfig physicsConfigOf(const SceneDef& d, double time_step, const Material& surface,
                              double real_time_factor) {
  PhysicsConfig c;
  c.gravity_x = d.world.gravity.x();
  c.gravity_y = d.world.gravity.y();
  c.gravity_z = d.world.gravity.z();
  c.time_step = time_step;
  c.substeps = d.world.solver.substeps;
  c.position_iterations = d.world.solver.position_iterations;
  c.static_friction = surface.static_friction;
  c.kinetic_friction = surface.kinetic_friction;
  c.restitution = surface.restitution;
  c.real_time_factor = real_time_factor;
  const SleepDef& s = d.world.sleep;
  c.sleep_enabled = s.enabled;
  c.sleep_time = s.time;
  c.sleep_speed = s.speed;
  c.rest_time = s.rest_time;
  c.rest_substeps = s.rest_substeps;
  c.rest_relax_iterations = s.rest_relax_iterations;
  return c;
}

}  // namespace node
}  // namespace ragdoll_sim
