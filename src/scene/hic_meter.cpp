// HicMeter (injury.hpp): the Head Injury Criterion over windows that start and end on sample
// boundaries, from the running integral of the acceleration.
#include <cmath>

#include "ragdoll_sim/injury.hpp"

namespace ragdoll_sim {

namespace {
// A window as long as the limit, give or take the round-off of summed sample lengths, counts.
constexpr double kWindowSlack = 1e-6;  // relative
// The search is skipped only when its bound is clearly below the best so far: the bound and
// the windows' values round differently.
constexpr double kBoundSlack = 1e-9;  // relative

double pow25(double x) { return x * x * std::sqrt(x); }
}  // namespace

HicMeter::HicMeter(double window) : window_(window) {}

void HicMeter::reset() {
  time_ = integral_ = 0.0;
  ring_.clear();  // the rings keep their capacity
  peaks_.clear();
  hic_ = t1_ = t2_ = 0.0;
}

// A non-finite or negative acceleration counts as 0 (a fault guard's reset, not a hit): one
// bad sample must not poison the whole record.
void HicMeter::add(double accel_g, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) return;
  if (!(accel_g > 0.0) || !std::isfinite(accel_g)) accel_g = 0.0;
  if (ring_.count == 0) ring_.push({0.0, 0.0});  // the record's start is a boundary
  time_ += dt;
  integral_ += accel_g * dt;
  const double oldest = time_ - window_ * (1.0 + kWindowSlack);
  while (ring_.count > 0 && ring_.front().t_end < oldest) ring_.popFront();
  // A sample is inside the ring while it ends after the ring's first boundary.
  const double start = ring_.count > 0 ? ring_.front().t_end : time_ - dt;
  while (peaks_.count > 0 && peaks_.front().t_end <= start) peaks_.popFront();
  while (peaks_.count > 0 && peaks_.back().accel <= accel_g) peaks_.popBack();
  peaks_.push({time_, accel_g});
  if ((time_ - start) * pow25(peaks_.front().accel) * (1.0 + kBoundSlack) > hic_) {
    for (size_t i = 0; i < ring_.count; ++i) {
      const Sample& s = ring_[i];
      const double T = time_ - s.t_end;
      const double mean = (integral_ - s.integral) / T;
      if (!(T > 0.0) || !(mean > 0.0)) continue;
      const double hic = T * pow25(mean);
      if (hic > hic_) {
        hic_ = hic;
        t1_ = s.t_end;
        t2_ = time_;
      }
    }
  }
  ring_.push({time_, integral_});
}

}  // namespace ragdoll_sim
