// The ranges of WorldDef, SolverSettings and SleepDef, in one place: World's constructor and setters
// throw with these messages, and the node's parameter check puts "parameter ~" in front of
// them (its parameters are named after the same fields).
#include <sstream>

#include "ragdoll_sim/range_check.hpp"
#include "ragdoll_sim/world.hpp"
#include "world_tuning.hpp"

namespace ragdoll_sim {

std::string sleepDefError(const SleepDef& s) {
  return firstError({nonNegativeError("time", s.time), nonNegativeError("speed", s.speed),
                     nonNegativeError("island_speed", s.island_speed),
                     nonNegativeError("rest_time", s.rest_time),
                     intRangeError("rest_substeps", s.rest_substeps, 0, INT_MAX, " (0 = off)"),
                     intRangeError("rest_relax_iterations", s.rest_relax_iterations, 0)});
}

std::string solverSettingsError(const SolverSettings& d) {
  // Hertz 0 is a rigid row (softness.hpp); a negative one, or a negative damping ratio, would
  // make the soft step's implicit spring gain energy.
  return firstError({
      intRangeError("substeps", d.substeps, 1),
      intRangeError("contact_relax_iterations", d.contact_relax_iterations, 0),
      intRangeError("joint_relax_iterations", d.joint_relax_iterations, 0),
      intRangeError("position_iterations", d.position_iterations, 0),
      intRangeError("anchor_iterations", d.anchor_iterations, 0),
      rangeError("position_factor", d.position_factor, 0.0, 1.0),
      nonNegativeError("max_position_correction", d.max_position_correction),
      nonNegativeError("joint_slop", d.joint_slop),
      nonNegativeError("angular_slop", d.angular_slop),
      nonNegativeError("max_angular_correction", d.max_angular_correction),
      nonNegativeError("contact_hertz", d.contact_hertz),
      nonNegativeError("contact_damping_ratio", d.contact_damping_ratio),
      nonNegativeError("joint_hertz", d.joint_hertz),
      nonNegativeError("joint_damping_ratio", d.joint_damping_ratio),
      nonNegativeError("max_push_velocity", d.max_push_velocity),
      nonNegativeError("restitution_threshold", d.restitution_threshold),
      nonNegativeError("static_friction_speed", d.static_friction_speed),
      nonNegativeError("speculative_distance", d.speculative_distance),
      nonNegativeError("linear_slop", d.linear_slop),
      positiveError("max_linear_speed", d.max_linear_speed),
      positiveError("max_angular_speed", d.max_angular_speed),
      d.lanes == 0 || d.lanes == 1 || d.lanes == 4 || d.lanes == 8
          ? std::string()
          : "lanes must be 0 (the widest), 1 (double rows), 4 or 8, got " + std::to_string(d.lanes),
  });
}

std::string worldDefError(const WorldDef& d) {
  if (!d.gravity.allFinite()) {
    std::ostringstream s;
    s << "gravity must be finite, got (" << d.gravity.x() << ", " << d.gravity.y() << ", "
      << d.gravity.z() << ")";
    return s.str();
  }
  std::string e = firstError({
      solverSettingsError(d.solver),
      intRangeError("threads", d.threads, 0, WorldDef::kMaxThreads, " (0 = all cores)"),
  });
  if (!e.empty()) return e;
  if (!(e = sleepDefError(d.sleep)).empty()) return "sleep." + e;
  return d.materials.error();
}

std::string worldTuningError(const WorldTuning& t) {
  return firstError({nonNegativeError("manifold_cache_distance", t.manifold_cache_distance),
                     intRangeError("range_reserve", t.range_reserve, -1, 1)});
}

}  // namespace ragdoll_sim
