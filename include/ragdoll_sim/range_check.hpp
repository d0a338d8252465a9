// Range checks that name what they check, so that a rule and its wording live once: the core's
// def checks (worldDefError, sleepDefError, materialError) and the node's parameter checks
// (which put "parameter ~" in front) share them. Each returns "" when the value is in range.
#pragma once

#include <climits>
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

}  // namespace ragdoll_sim
