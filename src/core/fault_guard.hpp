// The fault guard's data (fault_guard.cpp). Before the step every body whose state, force or
// torque is not finite, or whose centre of mass is beyond kWorldRange, goes back to its last
// good pose (finite and in range; kept per body, no allocation) with zero velocity, and every
// velocity is clamped to the caps (a huge impulse never reaches the solver); after the solve a
// body the solver left non-finite or out of range is reset the same way, and the warm-start
// impulses of its joints and contacts are cleared. Each reset is a BodyFault.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "body.hpp"
#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {

struct FaultGuardData {
  // Per body its last good pose, finite and in range (saved before and after each step; a
  // reset zeroes the velocity, so none is kept).
  struct FinitePose {
    Vec3 x;
    Quat q;
  };
  std::vector<FinitePose> last_finite;
  // Per body: the last step's finish checked and clamped it (finishMotion) and nothing changed
  // it since (wake clears it, setSolverSettings all): the guard before the next step would
  // change no bit of it, so it skips it.
  std::vector<char> guard_clean;
  std::vector<BodyFault> faults;  // not yet taken
  int64_t fault_count = 0;
  std::vector<char> solver_reset;  // per body: reset by this step's solver
  bool any_solver_reset = false;
  // finishBody found it non-finite (kSolverFault) or out of range (kRangeFault): resetFaulted
  // resets it.
  std::vector<char> solver_fault;
  static constexpr char kSolverFault = 1, kRangeFault = 2;
};

// One test instead of one per component: NaN or inf anywhere makes the sum non-finite. Finite
// values whose sum overflows fall through to the exact check.
inline bool motionFinite(const BodyMotion& m) {
  if (std::isfinite(m.x.sum() + m.q.coeffs().sum() + m.v.sum() + m.w.sum())) return true;
  return m.x.allFinite() && m.q.coeffs().allFinite() && m.v.allFinite() && m.w.allFinite();
}

inline bool inputsFinite(const BodyMotion& m) {
  if (std::isfinite(m.force.sum() + m.torque.sum())) return motionFinite(m);
  return m.force.allFinite() && m.torque.allFinite() && motionFinite(m);
}

// Scales a finite v down to length `max` when longer (also when its norm overflows). The
// squared test first: it spares the square root for nearly every call.
inline void clampNorm(Vec3& v, double max) {
  if (v.squaredNorm() <= max * max) return;
  double n = v.norm();
  if (n <= max) return;
  if (!std::isfinite(n)) n = v.stableNorm();
  v *= max / n;
}

}  // namespace ragdoll_sim
