// HicMeter (injury.hpp): the Head Injury Criterion over windows that start and end on sample
// boundaries, from the running integral of the acceleration.
#include <cmath>

#include "ragdoll_sim/injury.hpp"

namespace ragdoll_sim {

namespace {
// A window as long as the limit, give or take the round-off of summed sample lengths, counts.
constexpr double kWindowSlack = 1e-6;  // relative
}  // namespace

HicMeter::HicMeter(double window) : window_(window) {}

void HicMeter::reset() {
  time_ = integral_ = 0.0;
  ring_.clear();  // keeps its capacity
  hic_ = t1_ = t2_ = 0.0;
}

// A non-finite or negative acceleration counts as 0 (a fault guard's reset, not a hit): one
// bad sample must not poison the whole record.
void HicMeter::add(double accel_g, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) return;
  if (!(accel_g > 0.0) || !std::isfinite(accel_g)) accel_g = 0.0;
  if (ring_.empty()) ring_.push_back({0.0, 0.0});  // the record's start is a boundary
  time_ += dt;
  integral_ += accel_g * dt;
  const double oldest = time_ - window_ * (1.0 + kWindowSlack);
  size_t expired = 0;
  while (expired < ring_.size() && ring_[expired].t_end < oldest) ++expired;
  ring_.erase(ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(expired));
  for (const Sample& s : ring_) {
    const double T = time_ - s.t_end;
    const double mean = (integral_ - s.integral) / T;
    if (!(T > 0.0) || !(mean > 0.0)) continue;
    const double hic = T * mean * mean * std::sqrt(mean);
    if (hic > hic_) {
      hic_ = hic;
      t1_ = s.t_end;
      t2_ = time_;
    }
  }
  ring_.push_back({time_, integral_});
}

}  // namespace ragdoll_sim
