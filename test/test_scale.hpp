// Length of the longest test simulations: RAGDOLL_SIM_TEST_SCALE (0 < s <= 1, default 1)
// shrinks their step counts or the number of drops they run. scripts/sanitize.sh sets it, since
// ASan + UBSan run the solver about ten times slower; the checks stay the same, over less.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace test_scale {

inline double factor() {
  const char* s = std::getenv("RAGDOLL_SIM_TEST_SCALE");
  if (!s) return 1.0;
  const double f = std::atof(s);
  return f > 0.0 && f <= 1.0 ? f : 1.0;
}

// n scaled, but never below at_least.
inline int count(int n, int at_least) {
  return std::max(at_least, static_cast<int>(std::lround(n * factor())));
}

}  // namespace test_scale
