// Wall-clock pacing of the physics at a real-time factor (ROS-free, unit-tested with made-up
// time points). Step k after the last restart is due at anchor + k * dt / real_time_factor.
#pragma once

#include <chrono>
#include <cstdint>

namespace ragdoll_sim {
namespace scene {

class Pacer {
 public:
  using Clock = std::chrono::steady_clock;

  // dt_ns: physics step; real_time_factor: sim seconds per wall second, <= 0 or inf = as fast
  // as possible; max_catchup_steps: most steps one take() returns, and the backlog beyond
  // which late steps are dropped (sim time then falls behind instead of spiralling).
  void configure(int64_t dt_ns, double real_time_factor, int max_catchup_steps);
  // Real time counts from `now` again (start, unpause, a new dt or factor).
  void restart(Clock::time_point now);

  bool asFastAsPossible() const { return period_ns_ <= 0.0; }
  // Steps due at `now` (at most max_catchup_steps); the caller runs them. As fast as
  // possible: always max_catchup_steps. Drops a backlog of more than max_catchup_steps.
  int take(Clock::time_point now);
  // When the next step is due (`now` when as fast as possible).
  Clock::time_point next(Clock::time_point now) const;
  int64_t droppedSteps() const { return dropped_; }

 private:
  Clock::time_point due(int64_t k) const;
  double period_ns_ = 1e6;  // wall ns per step; <= 0: as fast as possible
  int max_steps_ = 100;
  Clock::time_point anchor_;
  int64_t taken_ = 0;       // steps since the anchor (taken or dropped)
  int64_t dropped_ = 0;
};

// Real-time factor as configured: 0 and inf mean as fast as possible; otherwise it must be
// >= kMinRealTimeFactor. Returns "" or the problem.
constexpr double kMinRealTimeFactor = 0.01;
const char* realTimeFactorError(double rtf);

}  // namespace scene
}  // namespace ragdoll_sim
