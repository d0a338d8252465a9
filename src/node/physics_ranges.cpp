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

}  // namespace node
}  // namespace ragdoll_sim
