// Range checks that name what they check, so that a rule and its wording live once: the core's
// def checks (worldDefError, sleepDefError, materialError) and the node's parameter checks
// (which put "parameter ~" in front) share them. Each returns "" when the value is in range.
#pragma once

#include <climits>
#include <initializer_list>
#include <string>

namespace ragdoll_sim {

// "<name> must be a finite number > 0, got <v>"
std::string positiveError(const std::string& name, double v);
// "<name> must be a finite number >= 0, got <v>"
std::string nonNegativeError(const std::string& name, double v);
// "<name> must be a finite number in [lo, hi], got <v>"
std::string rangeError(const std::string& name, double v, double lo, double hi);
// "<name> must be >= lo[ and <= hi]<note>, got <v>"; note e.g. " (0 = off)"
std::string intRangeError(const std::string& name, int v, int lo, int hi = INT_MAX,
                          const char* note = "");
// "<name> must be finite, got <v>"
std::string finiteError(const std::string& name, double v);
// "<name> must be > 0 (or inf), got <v>": break forces, "never" allowed
std::string positiveOrInfError(const std::string& name, double v);
// "<name> must be >= 0 (or inf), got <v>": caps, "no cap" allowed
std::string nonNegativeOrInfError(const std::string& name, double v);
// "<lo_name> must be <= <hi_name>, got <lo> > <hi>": NaN fails, infinite ends pass
std::string orderError(const std::string& lo_name, double lo, const std::string& hi_name,
                       double hi);
// The first non-empty message, or "".
std::string firstError(std::initializer_list<std::string> errors);

}  // namespace ragdoll_sim
