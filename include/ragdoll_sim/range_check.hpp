// Range checks that name what they check, so that a rule and its wording live once: the core's
// def checks (worldDefError, sleepDefError, materialError) and the node's parameter checks
// (which put "parameter ~" in front) share them. Each returns "" when the value is in range,
// without building a string: setJointMotor runs them every step for the balance law's motors.
#pragma once

#include <climits>
#include <initializer_list>
#include <string>
#include <string_view>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

// "<name> must be a finite number > 0, got <v>"
std::string positiveError(std::string_view name, double v);
// "<name> must be a finite number >= 0, got <v>"
std::string nonNegativeError(std::string_view name, double v);
// "<name> must be a finite number in [lo, hi], got <v>"
std::string rangeError(std::string_view name, double v, double lo, double hi);
// "<name> must be >= lo[ and <= hi]<note>, got <v>"; note e.g. " (0 = off)"
std::string intRangeError(std::string_view name, int v, int lo, int hi = INT_MAX,
                          const char* note = "");
// "<name> must be finite, got <v>"
std::string finiteError(std::string_view name, double v);
// "<name> must be > 0 (or inf), got <v>": break forces, "never" allowed
std::string positiveOrInfError(std::string_view name, double v);
// "<name> must be >= 0 (or inf), got <v>": caps, "no cap" allowed
std::string nonNegativeOrInfError(std::string_view name, double v);
// "<lo_name> must be <= <hi_name>, got <lo> > <hi>": NaN fails, infinite ends pass
std::string orderError(std::string_view lo_name, double lo, std::string_view hi_name,
                       double hi);
// "<name> must be a finite number > 0 and <= 1048576 (m, kWorldRange), got <v>"; with
// zero_allowed, >= 0: a size the World can hold
std::string lengthError(std::string_view name, double v, bool zero_allowed = false);
// "<name> must be finite and within 1048576 m (kWorldRange), got <x y z>": a point or an offset
// the World can hold (hull vertices, the URDF loader's <origin>s, poseError's offset)
std::string worldPointError(std::string_view name, const Vec3& p);
// "<name> must be a finite pose within 1048576 m (kWorldRange)": q finite and not zero, p as
// worldPointError's (an offset within a body: shapes, joint frames)
std::string poseError(std::string_view name, const Transform& t);
// The first non-empty message, or "".
std::string firstError(std::initializer_list<std::string> errors);

}  // namespace ragdoll_sim
