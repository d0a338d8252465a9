#include "pacing.hpp"

#include <cmath>

namespace ragdoll_sim {
namespace scene {

void Pacer::configure(int64_t dt_ns, double rtf, int max_catchup_steps) {
  period_ns_ = (rtf > 0.0 && std::isfinite(rtf)) ? static_cast<double>(dt_ns) / rtf : 0.0;
  max_steps_ = max_catchup_steps > 0 ? max_catchup_steps : 1;
}

void Pacer::restart(Clock::time_point now) {
  anchor_ = now;
  taken_ = 0;
}

Pacer::Clock::time_point Pacer::due(int64_t k) const {
  return anchor_ + std::chrono::nanoseconds(std::llround(static_cast<double>(k) * period_ns_));
}

int Pacer::take(Clock::time_point now) {
  if (asFastAsPossible()) return max_steps_;
  int n = 0;
  while (n < max_steps_ && due(taken_ + n) <= now) ++n;
  taken_ += n;
  if (due(taken_ + max_steps_) <= now) {
    // More than max_steps behind: skip the backlog (the steps still due now).
    const auto late = std::chrono::duration<double, std::nano>(now - due(taken_)).count();
    const int64_t skip = static_cast<int64_t>(late / period_ns_);
    taken_ += skip;
    dropped_ += skip;
  }
  return n;
}

Pacer::Clock::time_point Pacer::next(Clock::time_point now) const {
  return asFastAsPossible() ? now : due(taken_);
}

const char* realTimeFactorError(double rtf) {
  if (std::isnan(rtf) || rtf < 0.0) return "must be >= 0 (0 or .inf = as fast as possible)";
  if (rtf > 0.0 && rtf < kMinRealTimeFactor) return "must be 0 (as fast as possible) or >= 0.01";
  return "";
}

}  // namespace scene
}  // namespace ragdoll_sim
