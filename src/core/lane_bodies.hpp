// The double solver bodies (SolverBody, body.hpp) as the wide kernels see them: a base pointer
// and a stride, so a kernel file compiled with -mavx2 needs neither Eigen nor body.hpp (see
// lanes.hpp for why). The load and the write-back are lane_bodies.inc.
#pragma once

namespace ragdoll_sim {

struct SolverBody;

// Body i's v (3 doubles), then w (3 doubles) and its inverse mass (kLaneInvMass), from
// v + i * stride, 32-byte aligned; its dq (x, y, z, w) and dp kLaneDq and kLaneDp doubles after
// v, and its world inverse inertia (9 doubles, column by column) kLaneInvInertia doubles after v.
constexpr int kLaneInvMass = 6, kLaneDq = 8, kLaneDp = 12, kLaneInvInertia = 15;
struct LaneBodies {
  double* v = nullptr;
  int stride = 0;  // doubles
};

// The view of the solver bodies from the first (lane_bodies.cpp checks the layout the kernels
// rely on).
LaneBodies laneBodies(SolverBody* first);

}  // namespace ragdoll_sim
