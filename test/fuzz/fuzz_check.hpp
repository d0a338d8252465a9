// The fuzz targets' invariant check: a broken invariant is a crash for libFuzzer, which saves
// the input as an artifact. FUZZ_TARGET_NAME names the target in the message.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "ragdoll_sim/math.hpp"

#define FUZZ_CHECK(cond, ...)                                                       \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::fprintf(stderr, "%s: check failed: %s: ", FUZZ_TARGET_NAME, #cond);     \
      std::fprintf(stderr, __VA_ARGS__);                                            \
      std::fprintf(stderr, "\n");                                                   \
      std::abort();                                                                 \
    }                                                                               \
  } while (0)

namespace ragdoll_sim {
namespace fuzz {

inline bool finite(const Transform& t) { return t.p.allFinite() && t.q.coeffs().allFinite(); }

}  // namespace fuzz
}  // namespace ragdoll_sim
