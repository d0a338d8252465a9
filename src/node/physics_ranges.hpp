// The ranges of the physics settings, one definition for start-up and run time: the min / max
// of cfg/Physics.cfg (read from the generated PhysicsConfig) plus the real-time factor's rule
// that a min cannot say (0 = as fast as possible, else at least scene::kMinRealTimeFactor).
#pragma once

#include <string>

#include "ragdoll_sim/PhysicsConfig.h"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace node {

struct RangeProblem {
  std::string field;  // the .cfg name, e.g. "substeps"
  double value = 0.0;
  std::string rule;   // e.g. "[1, 64]" or "0 (as fast as possible) or [0.01, 1000]"
  bool ok() const { return field.empty(); }
};

// The first value of `c` outside its range (NaN is outside every range; +inf as the
// real-time factor means as fast as possible, as 0 does), or ok(). Values equal to those in
// `in_force` pass: a request is judged by what it changes (a named surface of ~materials may
// hold a friction beyond the .cfg's range).
RangeProblem physicsRangeProblem(const ragdoll_sim::PhysicsConfig& c,
                                 const ragdoll_sim::PhysicsConfig* in_force = nullptr);

// The settings of `d` as the .cfg's fields: the step `time_step` (s), friction and restitution
// of `surface`, and `real_time_factor` as given.
ragdoll_sim::PhysicsConfig physicsConfigOf(const SceneDef& d, double time_step,
                                           const Material& surface, double real_time_factor);

// The rule of a .cfg field as text, e.g. "[1e-05, 0.05]"; "" for an unknown field.
std::string physicsRangeRule(const std::string& field);

}  // namespace node
}  // namespace ragdoll_sim
