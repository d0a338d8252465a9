#include "warn_throttle.hpp"

namespace ragdoll_sim {
namespace scene {

bool WarnThrottle::allow(const std::string& kind, double now_s, uint64_t* suppressed) {
  auto [it, fresh] = kinds_.try_emplace(kind);
  Entry& e = it->second;
  if (!fresh && now_s - e.last < period_) {
    ++e.held;
    return false;
  }
  *suppressed = e.held;
  e.held = 0;
  e.last = now_s;
  return true;
}

}  // namespace scene
}  // namespace ragdoll_sim
