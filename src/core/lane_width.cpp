#include "lane_width.hpp"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ragdoll_sim {

bool cpuHasAvx2() {
#if defined(RAGDOLL_SIM_HAVE_LANES8) && (defined(__x86_64__) || defined(__i386__))
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

bool cpuHasAvx512() {
#if defined(RAGDOLL_SIM_HAVE_LANES16) && (defined(__x86_64__) || defined(__i386__))
  static const bool has = cpuHasAvx2() && __builtin_cpu_supports("avx512f");
  return has;
#else
  return false;
#endif
}

int chooseLaneWidth(int requested, const char* env, bool has_avx2) {
  int width = requested;
  if (width != 0 && width != 4 && width != 8)
    throw std::invalid_argument("lane width " + std::to_string(requested) +
                                ": expected 0 (automatic), 4 or 8");
  if (width == 0 && !laneWidthAutomatic(0, env)) {
    if (std::strcmp(env, "4") == 0) width = 4;
    else if (std::strcmp(env, "8") == 0) width = 8;
    else
      throw std::invalid_argument(std::string("RAGDOLL_SIM_LANES=") + env + ": expected 4 or 8");
  }
  if (width == 0) width = 8;
  return width == 8 && !has_avx2 ? 4 : width;
}

int chooseLaneWidth(int requested) {
  return chooseLaneWidth(requested, std::getenv("RAGDOLL_SIM_LANES"), cpuHasAvx2());
}

bool laneWidthAutomatic(int requested, const char* env) {
  return requested == 0 && (env == nullptr || *env == '\0');
}

bool laneWidthAutomatic(int requested) {
  return laneWidthAutomatic(requested, std::getenv("RAGDOLL_SIM_LANES"));
}

}  // namespace ragdoll_sim
