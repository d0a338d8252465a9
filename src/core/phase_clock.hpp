// The step's phase timer behind World::stepProfile: each lap adds the time since the last one to
// a field of the profile; off, a lap is one branch.
#pragma once

#include <chrono>

namespace ragdoll_sim {

class PhaseClock {
 public:
  explicit PhaseClock(bool on) : on_(on) {
    if (on_) last_ = Clock::now();
  }
  void lap(double& us) {
    if (!on_) return;
    const Clock::time_point now = Clock::now();
    us += std::chrono::duration<double, std::micro>(now - last_).count();
    last_ = now;
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool on_;
  Clock::time_point last_;
};

}  // namespace ragdoll_sim
