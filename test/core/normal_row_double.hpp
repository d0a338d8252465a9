// A copy of contact_solver.cpp's rigid normal row in double (PairVelocity and the normal loop
// of solveConstraint, one point at a time), for test_lanes.cpp and bench/bench_lanes.cpp to
// compare the float-lane kernel with.
#pragma once

#include <algorithm>
#include <vector>

#include "body.hpp"
#include "contact_solver.hpp"

namespace ragdoll_sim {
namespace lane_test {

struct NormalRowD {
  int a, b;  // into the SolverBody array, -1: static (an identity body)
  Vec3 normal;
  ContactRow row;
  double separation, impulse, max_impulse;
};

struct NormalRowParamsD {
  double inv_h, bias_rate, mass_scale, impulse_scale, linear_slop, max_push_velocity;
  bool use_bias;
};

template <bool kLiveA>
void solveNormalRowD(NormalRowD& p, SolverBody& A, SolverBody& B, const NormalRowParamsD& k) {
  Vec3 vA = A.v, wA = A.w, vB = B.v, wB = B.w;
  const double mA = A.inv_mass, mB = B.inv_mass;
  const double s = p.separation;
  double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
  if (s > 0.0) {
    bias = s * k.inv_h;
  } else if (k.use_bias) {
    bias = std::max(k.bias_rate * std::min(s + k.linear_slop, 0.0), -k.max_push_velocity);
    mass_scale = k.mass_scale;
    impulse_scale = k.impulse_scale;
  }
  const Vec3& d = p.normal;
  const double vn = kLiveA ? d.dot(vB - vA) + wB.dot(p.row.angB) - wA.dot(p.row.angA)
                           : d.dot(vB) + wB.dot(p.row.angB);
  if (vn < 0.0) mass_scale = 1.0, impulse_scale = 0.0;
  double lambda = -p.row.mass * mass_scale * (vn + bias) - impulse_scale * p.impulse;
  const double next = std::max(p.impulse + lambda, 0.0);
  lambda = next - p.impulse;
  p.impulse = next;
  p.max_impulse = std::max(p.max_impulse, lambda);
  if (kLiveA) {
    vA -= (mA * lambda) * d;
    wA -= lambda * p.row.iangA;
  }
  vB += (mB * lambda) * d;
  wB += lambda * p.row.iangB;
  if (kLiveA) {
    A.v = vA;
    A.w = wA;
  }
  B.v = vB;
  B.w = wB;
}

// One sweep over the rows in order; a static side is an identity body.
inline void solveNormalRowsD(std::vector<NormalRowD>& rows, std::vector<SolverBody>& bodies,
                             const NormalRowParamsD& k) {
  SolverBody ground;
  for (NormalRowD& p : rows) {
    SolverBody& B = p.b >= 0 ? bodies[p.b] : ground;
    if (p.a >= 0) solveNormalRowD<true>(p, bodies[p.a], B, k);
    else solveNormalRowD<false>(p, ground, B, k);
  }
}

}  // namespace lane_test
}  // namespace ragdoll_sim
