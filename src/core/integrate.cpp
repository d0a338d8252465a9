// The per-body phases of the island solve: the solver body prepared at the step start, and the
// velocities and positions advanced in each substep (semi-implicit Euler, island_solve.hpp).
#include "integrate_kernel.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

// The solver body of body i at the step start: an awake body's velocities, inverse mass
// and world inverse inertia, an identity state for the others.
void World::Impl::prepareSolverBody(int i) {
  const BodyMotion& m = motions[i];
  SolverBody& s = solver[i];
  if (!m.awake) {
    s = SolverBody();
    return;
  }
  const Mat3& R = rotations[i] = m.q.toRotationMatrix();
  s.dp.setZero();
  s.dq = Quat::Identity();
  s.moved_sweep = 0;
  s.v = m.v;
  s.w = m.w;
  s.inv_mass = m.inv_mass;
  s.inv_inertia = R * m.inv_inertia_local * R.transpose();
}

void World::Impl::integrateVelocities(double h, int begin, int end) {
  for (int k = begin; k < end; ++k) {
    const int i = island_bodies[k];
    const BodyMotion& m = motions[i];
    SolverBody& s = solver[i];
    const Vec3 a = m.gravity_scale * def.gravity + m.inv_mass * m.force;
    s.v = (s.v + h * a) / (1.0 + h * m.linear_damping);
    s.w = (s.w + h * (s.inv_inertia * m.torque)) / (1.0 + h * m.angular_damping);
    // Clamped per substep as well as at the step end (as Box2D v3 does): a torque at the
    // command cap on a light link otherwise spins it so fast within one step that the joints
    // fling their neighbours away.
    clampNorm(s.v, def.solver.max_linear_speed);
    clampNorm(s.w, def.solver.max_angular_speed);
  }
}

// The rotation advances with w; then w is recomputed from the world angular momentum
// L = R I R^T w, which free rotation conserves: w' = R' I^-1 R'^T L. This is the gyroscopic
// term (precession, the middle-axis flip) and keeps L exact in free flight. Two loops: the
// first parks L in w, the second turns it back; each body's chain (a square root and a division
// in the middle) is then short enough for the core to overlap bodies. Bodies go two at a time
// through the SSE2 lanes (integrate_kernel.hpp: each lane does the one-body operations).
void World::Impl::integratePositions(double h, int begin, int end) {
  using namespace integrate_kernel;
  const double half_h = 0.5 * h;
  const Double2 h2 = {h, h}, half_h2 = {half_h, half_h};
  int k = begin;
  for (; k + 1 < end; k += 2) {
    const int i0 = island_bodies[k], i1 = island_bodies[k + 1];
    const BodyMotion &m0 = motions[i0], &m1 = motions[i1];
    SolverBody &s0 = solver[i0], &s1 = solver[i1];
    double *R0 = rotations[i0].data(), *R1 = rotations[i1].data();
    Double2 v[3], dp[3], w[3], dq[4], R[9], inertia[9], q[4];
    gather<3>(s0.v.data(), s1.v.data(), v);
    gather<3>(s0.dp.data(), s1.dp.data(), dp);
    gather<3>(s0.w.data(), s1.w.data(), w);
    gather<4>(s0.dq.coeffs().data(), s1.dq.coeffs().data(), dq);
    gather<9>(R0, R1, R);
    gather<9>(m0.inertia_local.data(), m1.inertia_local.data(), inertia);
    gather<4>(m0.q.coeffs().data(), m1.q.coeffs().data(), q);
    advanceRotation(h2, half_h2, v, dp, w, dq, R, inertia, q);
    scatter<3>(dp, s0.dp.data(), s1.dp.data());
    scatter<3>(w, s0.w.data(), s1.w.data());
    scatter<4>(dq, s0.dq.coeffs().data(), s1.dq.coeffs().data());
    scatter<9>(R, R0, R1);
  }
  if (k < end) {
    const int i = island_bodies[k];
    const BodyMotion& m = motions[i];
    SolverBody& s = solver[i];
    advanceRotation(h, half_h, s.v.data(), s.dp.data(), s.w.data(), s.dq.coeffs().data(),
                    rotations[i].data(), m.inertia_local.data(), m.q.coeffs().data());
  }
  for (k = begin; k + 1 < end; k += 2) {
    const int i0 = island_bodies[k], i1 = island_bodies[k + 1];
    SolverBody &s0 = solver[i0], &s1 = solver[i1];
    Double2 w[3], R[9], inv_inertia[9];
    gather<3>(s0.w.data(), s1.w.data(), w);
    gather<9>(rotations[i0].data(), rotations[i1].data(), R);
    gather<9>(motions[i0].inv_inertia_local.data(), motions[i1].inv_inertia_local.data(),
              inv_inertia);
    finishRotation(R, inv_inertia, w);
    scatter<3>(w, s0.w.data(), s1.w.data());
  }
  if (k < end) {
    const int i = island_bodies[k];
    finishRotation(rotations[i].data(), motions[i].inv_inertia_local.data(), solver[i].w.data());
  }
}

}  // namespace ragdoll_sim
