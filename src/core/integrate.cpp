// The per-body phases of the island solve: the solver body prepared at the step start, and the
// velocities and positions advanced in each substep (semi-implicit Euler, island_solve.hpp).
#include <algorithm>

#include "integrate.hpp"
#include "lane_width.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

static_assert(sizeof(Mat3) == 9 * sizeof(double), "rotations are read as 9 doubles a body");

integrate_kernel::BodyFields bodyFields(std::vector<SolverBody>& solver,
                                        std::vector<BodyMotion>& motions,
                                        std::vector<Mat3>& rotations) {
  const SolverBody& s = solver[0];
  const BodyMotion& m = motions[0];
  const auto at = [](const void* field, const void* base) {
    return long((const char*)field - (const char*)base);
  };
  integrate_kernel::BodyFields f;
  f.solver = (char*)solver.data();
  f.solver_stride = sizeof(SolverBody);
  f.v = at(s.v.data(), &s);
  f.w = at(s.w.data(), &s);
  f.dp = at(s.dp.data(), &s);
  f.dq = at(s.dq.coeffs().data(), &s);
  f.world_inv_inertia = at(s.inv_inertia.data(), &s);
  f.motion = (char*)motions.data();
  f.motion_stride = sizeof(BodyMotion);
  f.x = at(m.x.data(), &m);
  f.x_carry = at(m.x_carry.data(), &m);
  f.inertia = at(m.inertia_local.data(), &m);
  f.inv_inertia = at(m.inv_inertia_local.data(), &m);
  f.q = at(m.q.coeffs().data(), &m);
  f.force = at(m.force.data(), &m);
  f.torque = at(m.torque.data(), &m);
  f.gravity_scale = at(&m.gravity_scale, &m);
  f.inv_mass = at(&m.inv_mass, &m);
  f.linear_damping = at(&m.linear_damping, &m);
  f.angular_damping = at(&m.angular_damping, &m);
  f.rotations = rotations[0].data();
  return f;
}

namespace {

// An awake body's solver body at the step start, but for its world inverse inertia.
void startSolverBody(const BodyMotion& m, SolverBody& s) {
  s.dp.setZero();
  s.dq = Quat::Identity();
  s.moved_sweep = 0;
  s.v = m.v;
  s.w = m.w;
  s.inv_mass = m.inv_mass;
}
}  // namespace

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
  startSolverBody(m, s);
  s.inv_inertia = R * m.inv_inertia_local * R.transpose();
}

// An island's bodies (all awake): as prepareSolverBody, with the rotations and world inverse
// inertias four bodies at a time in AVX lanes, or two in SSE2 lanes, by byLaneWidth (the same
// bits, integrate_kernel.hpp).
void World::Impl::prepareSolverBodies(int begin, int end, const StepContext& c) {
  if (begin >= end) return;
  std::vector<SolverBody>& solver = *c.bodies;
  for (int k = begin; k < end; ++k) {
    const int i = island_bodies[k];
    startSolverBody(motions[i], solver[i]);
  }
  using namespace integrate_kernel;
  const BodyFields f = bodyFields(solver, motions, *c.rotations);
  byLaneWidth(island_bodies.data() + begin, end - begin, [&](int width, const int* b, int n) {
    if (width == 4) integrate_w4::prepareRotations(f, b, n);
    else prepareRotations<Double2>(f, b, n);
  });
}

// The pose part of finishBody for island_bodies[begin, end) (all awake), by lane width as above.
void World::Impl::finishPoses(int begin, int end, const StepContext& c) {
  if (begin >= end) return;
  using namespace integrate_kernel;
  const BodyFields f = bodyFields(*c.bodies, motions, *c.rotations);
  const double grid = kPositionGrid, range = kWorldRange;
  byLaneWidth(island_bodies.data() + begin, end - begin, [&](int width, const int* b, int n) {
    if (width == 4) integrate_w4::finishPoses(f, b, n, grid, range);
    else integrate_kernel::finishPoses<Double2>(f, b, n, grid, range);
  });
}

// Four bodies at a time in AVX lanes where the CPU has AVX2 (integrate_kernel.hpp), a chunk at a
// time: the lanes find the few bodies that may need a clamp, which then run clampNorm. The last
// one to three go as four lanes that repeat the last body (byLaneWidth), which is clamped once.
// Without AVX2 one at a time here (the same bits).
void World::Impl::integrateVelocities(const StepContext& c, int begin, int end) {
  const double h = c.h;
  std::vector<SolverBody>& solver = *c.bodies;
  const double max_v = def.solver.max_linear_speed, max_w = def.solver.max_angular_speed;
  if (cpuHasAvx2()) {
    constexpr int kChunk = 64;  // a multiple of 4
    const integrate_kernel::BodyFields f = bodyFields(solver, motions, *c.rotations);
    const double max_v2 = max_v * max_v, max_w2 = max_w * max_w;
    int clamp[kChunk];
    byLaneWidth(island_bodies.data() + begin, end - begin, [&](int, const int* bodies, int n) {
      for (int k = 0; k < n; k += kChunk) {
        const int* chunk = bodies + k;
        const int clamped = integrate_w4::advanceVelocities(
            f, chunk, std::min(kChunk, n - k), h, def.gravity.data(), max_v2, max_w2, clamp);
        for (int j = 0; j < clamped; ++j) {
          // a repeated last body follows itself in the lanes: clamped once
          if (j > 0 && chunk[clamp[j]] == chunk[clamp[j - 1]]) continue;
          SolverBody& s = solver[chunk[clamp[j]]];
          clampNorm(s.v, max_v);
          clampNorm(s.w, max_w);
        }
      }
    });
    return;
  }
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
    clampNorm(s.v, max_v);
    clampNorm(s.w, max_w);
  }
}

// The rotation advances with w; then w is recomputed from the world angular momentum
// L = R I R^T w, which free rotation conserves: w' = R' I^-1 R'^T L. This is the gyroscopic
// term (precession, the middle-axis flip) and keeps L exact in free flight. Bodies go four at a
// time through AVX lanes where the CPU has AVX2, else two at a time through SSE2 lanes
// (byLaneWidth; integrate_kernel.hpp: each lane does the one-body operations, so all give the
// same bits); the lanes' side-by-side chains (a square root and a division in the middle) keep
// the core busy.
void World::Impl::integratePositions(const StepContext& c, int begin, int end) {
  if (begin >= end) return;
  using namespace integrate_kernel;
  const double h = c.h, half_h = 0.5 * h;
  const BodyFields f = bodyFields(*c.bodies, motions, *c.rotations);
  byLaneWidth(island_bodies.data() + begin, end - begin, [&](int width, const int* b, int n) {
    if (width == 4) integrate_w4::stepPositions(f, b, n, h, half_h);
    else stepPositions<Double2>(f, b, n, h, half_h);
  });
}

}  // namespace ragdoll_sim
