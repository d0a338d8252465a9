// Throttled warnings per problem kind. ROS_WARN_THROTTLE throttles per call site, so when one
// site reports many problems (every rule of a command check) a flood of one kind hides the
// others. This throttle keeps a clock per kind: each kind is named at least once per period,
// and what it held back is counted and told with the next one of that kind. ROS-free.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>

namespace ragdoll_sim {
namespace scene {

class WarnThrottle {
 public:
  explicit WarnThrottle(double period_s = 1.0) : period_(period_s) {}

  // True when a warning of `kind` may go out at time `now_s` (any monotonic clock, s); then
  // *suppressed holds how many of that kind were held back since the last one. Kinds must come
  // from a fixed set (not from message contents): the table keeps one entry per kind.
  bool allow(const std::string& kind, double now_s, uint64_t* suppressed);

 private:
  struct Entry {
    double last = 0.0;
    uint64_t held = 0;
  };
  double period_;
  std::unordered_map<std::string, Entry> kinds_;
};

}  // namespace scene
}  // namespace ragdoll_sim
