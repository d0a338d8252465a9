// Head injury metrics of a fall: the head's peak acceleration, the Head Injury Criterion over
// 15 and 36 ms windows, peak angular acceleration and the neck's peak reaction. No ROS; the
// Scene keeps one record per ragdoll (scene.hpp), ragdoll_check --injury prints it.
// docs/injury.md: definitions, and why the numbers of a rigid-body model depend on the contact
// compliance of the surfaces (Material::contact_hertz).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

constexpr double kStandardGravity = 9.80665;  // m/s^2: 1 g

// HIC of one window length from a sampled acceleration:
//   HIC = max over t1 < t2, t2 - t1 <= window, of (t2 - t1) * [1/(t2 - t1) * int a dt]^2.5
// with a the resultant acceleration in g and t in s. Each sample is the mean acceleration over
// its interval (a piecewise-constant signal, as a substep's velocity change over h is), so
// the integral over whole intervals is exact; windows start and end on sample boundaries.
// O(window / dt) per sample at most; nothing is allocated per sample once the rings are full.
class HicMeter {
 public:
  explicit HicMeter(double window = 0.015);  // s
  void reset();
  // One interval of length dt (s, > 0) with mean acceleration accel_g (g, >= 0).
  void add(double accel_g, double dt);
  double hic() const { return hic_; }
  double t1() const { return t1_; }  // s from the first sample, the window found
  double t2() const { return t2_; }
  double window() const { return window_; }

 private:
  // A queue, oldest first, in a vector whose size is a power of two (doubled when full).
  template <class T>
  struct Ring {
    std::vector<T> v;
    size_t first = 0, count = 0;
    T& operator[](size_t i) { return v[(first + i) & (v.size() - 1)]; }
    T& front() { return (*this)[0]; }
    T& back() { return (*this)[count - 1]; }
    void popFront() { first = (first + 1) & (v.size() - 1), --count; }
    void popBack() { --count; }
    void clear() { first = count = 0; }
    void push(const T& x) {
      if (count == v.size()) {
        std::vector<T> grown(v.empty() ? 16 : 2 * v.size());
        for (size_t i = 0; i < count; ++i) grown[i] = (*this)[i];
        v.swap(grown);
        first = 0;
      }
      ++count;
      back() = x;
    }
  };
  struct Sample {
    double t_end;     // s from the first sample
    double integral;  // int a dt from the start of the record to t_end (g s)
  };
  struct Peak {
    double t_end;  // of its sample
    double accel;  // g
  };
  double window_;
  double time_ = 0.0, integral_ = 0.0;
  Ring<Sample> ring_;  // the sample boundaries within `window_` of the newest
  // The samples inside the ring that no later one reaches (a sliding maximum): peaks_.front()
  // is the largest, and no window ending at the newest sample beats span * it^2.5, so most
  // samples (at rest, in flight) skip the search.
  Ring<Peak> peaks_;
  double hic_ = 0.0, t1_ = 0.0, t2_ = 0.0;
};

// Which links of a ragdoll are head and neck, and when a fall ends.
struct InjuryDef {
  // Off: no records and no tracked heads (nothing runs per step).
  bool enabled = true;
  // "" = the bundled ragdoll's (link "head"), else guessed by name (the first link whose name
  // holds "head" or "skull"), with an INFO line saying which, or that none is (no record).
  std::string head_link;
  // A RagdollDef joint name or one of its URDF joints ("neck_y" names the bundled ragdoll's
  // ball "neck_y+neck_x+neck_z"); "" = the joint whose child is the head.
  std::string neck_joint;
  // A fall starts when some link moves faster than fall_speed (its record covers the step
  // that found it) and ends once every link has been slower than rest_speed for rest_time (or
  // the ragdoll sleeps): its report is made then. Between falls nothing is measured.
  double fall_speed = 0.5;  // m/s
  double rest_speed = 0.05; // m/s
  double rest_time = 0.5;   // s
};

// One fall's metrics. Accelerations are the head's centre of mass's proper acceleration
// (what an accelerometer in it reads: dv/dt - gravity, 1 g at rest), from its velocity at the
// end of every substep.
struct InjuryReport {
  std::string ragdoll, head_link, neck_joint;
  std::string reason;               // "rest", "reset" (asked for) or "removed"
  double start_time = 0.0, end_time = 0.0;  // s of sim time the record covers
  double peak_g = 0.0;              // g
  double peak_time = 0.0;           // s of sim time
  double hic15 = 0.0, hic15_t1 = 0.0, hic15_t2 = 0.0;  // window in s of sim time
  double hic36 = 0.0, hic36_t1 = 0.0, hic36_t2 = 0.0;
  double peak_angular_acceleration = 0.0;  // rad/s^2
  double peak_neck_force = 0.0;     // N, |JointWrench::force| of the neck
  double peak_neck_torque = 0.0;    // N m, |JointWrench::torque|
};

}  // namespace ragdoll_sim
