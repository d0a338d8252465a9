// integrate_kernel.hpp against the Eigen expressions it replaces: one body (double), two
// (Double2 lanes) and four (AVX lanes, where the CPU has AVX2) must give the same bits as the
// Eigen code, whatever the inputs.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "fault_guard.hpp"
#include "integrate.hpp"
#include "lane_width.hpp"
#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {
namespace {

using namespace integrate_kernel;

struct BodyState {
  Vec3 v, dp, w;
  Quat dq, q;
  Mat3 R, inertia, inv_inertia;
};

// The Eigen code of integratePositions, one body.
void referenceStep(double h, BodyState& b) {
  b.dp += h * b.v;
  const Vec3 L = b.R * (b.inertia * (b.R.transpose() * b.w));
  const Vec3 hw = 0.5 * h * b.w;
  Quat dq = b.dq;
  dq.coeffs() += (Quat(0, hw.x(), hw.y(), hw.z()) * b.dq).coeffs();
  b.dq = dq.normalized();
  b.R = (b.dq * b.q).toRotationMatrix();
  b.w = b.R * (b.inv_inertia * (b.R.transpose() * L));
}

// The position step of bodies[0..n) through the arrays, `width` bodies at a time (4: the AVX
// kernel).
void arrayStep(double h, int width, std::vector<BodyState>& states) {
  const int n = int(states.size());
  std::vector<SolverBody> solver(n);
  std::vector<BodyMotion> motions(n);
  std::vector<Mat3> rotations(n);
  std::vector<int> bodies;
  for (int i = n - 1; i >= 0; --i) bodies.push_back(i);  // any order: each body alone
  for (int i = 0; i < n; ++i) {
    const BodyState& b = states[i];
    solver[i].v = b.v;
    solver[i].dp = b.dp;
    solver[i].w = b.w;
    solver[i].dq = b.dq;
    motions[i].q = b.q;
    motions[i].inertia_local = b.inertia;
    motions[i].inv_inertia_local = b.inv_inertia;
    rotations[i] = b.R;
  }
  const BodyFields f = bodyFields(solver, motions, rotations);
  if (width == 4) {
    integrate_w4::stepPositions(f, bodies.data(), n, h, 0.5 * h);
  } else if (width == 2) {
    stepPositions<Double2>(f, bodies.data(), n, h, 0.5 * h);
  } else {
    stepPositions<double>(f, bodies.data(), n, h, 0.5 * h);
  }
  for (int i = 0; i < n; ++i) {
    BodyState& b = states[i];
    b.v = solver[i].v;
    b.dp = solver[i].dp;
    b.w = solver[i].w;
    b.dq = solver[i].dq;
    b.R = rotations[i];
  }
}

template <class M>
bool sameBits(const M& x, const M& y) {
  return std::memcmp(x.data(), y.data(), sizeof(double) * x.size()) == 0;
}
bool sameBits(const BodyState& x, const BodyState& y) {
  return sameBits(x.v, y.v) && sameBits(x.dp, y.dp) && sameBits(x.w, y.w) &&
         sameBits(x.dq.coeffs(), y.dq.coeffs()) && sameBits(x.R, y.R);
}

BodyState randomBody(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  BodyState b;
  b.v = 5.0 * vec();
  b.dp = 0.1 * vec();
  b.w = 20.0 * vec();
  b.q = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
  b.dq = Quat(1.0 + 0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng)).normalized();
  b.R = Quat(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  const Mat3 A = Mat3::NullaryExpr([&] { return u(rng); });
  b.inertia = A * A.transpose() + 0.1 * Mat3::Identity();
  b.inv_inertia = b.inertia.inverse();
  if (kind == 1) b.w.setZero();                            // at rest: signed zeros
  if (kind == 2) b.dq = Quat(0.0, 0.0, 0.0, 0.0);          // the unnormalisable branch
  if (kind == 3) b.inv_inertia.setZero();                  // infinite inertia
  return b;
}

TEST(IntegrateKernel, OneTwoAndFourBodiesGiveTheEigenBits) {
  std::mt19937_64 rng(60);
  std::vector<int> widths = {1, 2};
  if (cpuHasAvx2()) widths.push_back(4);
  for (int n = 0; n < 5000; ++n) {
    const double h = (n % 7 + 1) * 1.0 / 240.0;
    std::vector<BodyState> start;
    for (int l = 0; l < 4; ++l) start.push_back(randomBody(rng, (n + l * (n / 5)) % 5));
    std::vector<BodyState> reference = start;
    for (BodyState& b : reference) referenceStep(h, b);
    for (const int width : widths) {
      std::vector<BodyState> states = start;
      arrayStep(h, width, states);
      for (int l = 0; l < 4; ++l)
        ASSERT_TRUE(sameBits(states[l], reference[l])) << "width " << width << ", lane " << l
                                                        << ", case " << n;
    }
  }
}

// integrateVelocities through the arrays, `width` bodies at a time, then clampNorm on the bodies
// the lanes flag, against its Eigen code with clampNorm on every body.
TEST(IntegrateKernel, VelocityStepGivesTheEigenBitsAtEachWidth) {
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  std::vector<int> widths = {1, 2};
  if (cpuHasAvx2()) widths.push_back(4);
  const Vec3 gravity(0.0, 0.0, -9.81);
  const double max_v = 8.0, max_w = 25.0;
  int flagged = 0;
  for (int n = 0; n < 5000; ++n) {
    const double h = (n % 7 + 1) * 1.0 / 240.0;
    std::vector<SolverBody> solver(4);
    std::vector<BodyMotion> motions(4);
    std::vector<Mat3> rotations(4);
    for (int l = 0; l < 4; ++l) {
      SolverBody& s = solver[l];
      BodyMotion& m = motions[l];
      s.v = 10.0 * vec();
      s.w = 30.0 * vec();
      if ((n + l) % 97 == 0) s.w.x() = std::nan("");
      const Mat3 A = Mat3::NullaryExpr([&] { return u(rng); });
      s.inv_inertia = (A * A.transpose()).inverse();
      m.force = 100.0 * vec();
      m.torque = (n + l) % 3 ? Vec3(10.0 * vec()) : Vec3::Zero();
      m.gravity_scale = (n + l) % 4 ? 1.0 : u(rng);
      m.inv_mass = 1.0 + u(rng);
      m.linear_damping = (n + l) % 2 ? 0.0 : 1.0 + u(rng);
      m.angular_damping = (n + l) % 5 ? 0.0 : 1.0 + u(rng);
    }
    std::vector<SolverBody> reference = solver;
    for (int l = 0; l < 4; ++l) {
      const BodyMotion& m = motions[l];
      SolverBody& s = reference[l];
      const Vec3 a = m.gravity_scale * gravity + m.inv_mass * m.force;
      s.v = (s.v + h * a) / (1.0 + h * m.linear_damping);
      s.w = (s.w + h * (s.inv_inertia * m.torque)) / (1.0 + h * m.angular_damping);
      clampNorm(s.v, max_v);
      clampNorm(s.w, max_w);
    }
    const int bodies[4] = {2, 0, 3, 1};
    for (const int width : widths) {
      std::vector<SolverBody> lanes = solver;
      const BodyFields f = bodyFields(lanes, motions, rotations);
      int clamp[4];
      const double g[3] = {gravity.x(), gravity.y(), gravity.z()};
      const double v2 = max_v * max_v, w2 = max_w * max_w;
      const int count =
          width == 4   ? integrate_w4::advanceVelocities(f, bodies, 4, h, g, v2, w2, clamp)
          : width == 2 ? advanceVelocities<Double2>(f, bodies, 4, h, g, v2, w2, clamp)
                       : advanceVelocities<double>(f, bodies, 4, h, g, v2, w2, clamp);
      flagged += count;
      for (int j = 0; j < count; ++j) {
        clampNorm(lanes[bodies[clamp[j]]].v, max_v);
        clampNorm(lanes[bodies[clamp[j]]].w, max_w);
      }
      for (int l = 0; l < 4; ++l)
        ASSERT_TRUE(sameBits(lanes[l].v, reference[l].v) && sameBits(lanes[l].w, reference[l].w))
            << "width " << width << ", body " << l << ", case " << n;
    }
  }
  EXPECT_GT(flagged, 0);
}

// The step-start rotation and world inverse inertia (prepareSolverBodies) against
// prepareSolverBody's Eigen code, at each width; the inputs include unnormalised quaternions
// (the lanes must not normalise) and a zero inverse inertia.
TEST(IntegrateKernel, StepStartRotationsGiveTheEigenBitsAtEachWidth) {
  std::mt19937_64 rng(62);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> widths = {1, 2};
  if (cpuHasAvx2()) widths.push_back(4);
  for (int n = 0; n < 5000; ++n) {
    std::vector<SolverBody> solver(4);
    std::vector<BodyMotion> motions(4);
    std::vector<Mat3> reference_R(4), reference_world(4);
    for (int l = 0; l < 4; ++l) {
      BodyMotion& m = motions[l];
      m.q = Quat(u(rng), u(rng), u(rng), u(rng));
      if ((n + l) % 3) m.q.normalize();
      const Mat3 A = Mat3::NullaryExpr([&] { return u(rng); });
      m.inv_inertia_local = (n + l) % 11 ? Mat3(A * A.transpose()) : Mat3::Zero();
      reference_R[l] = m.q.toRotationMatrix();
      reference_world[l] = reference_R[l] * m.inv_inertia_local * reference_R[l].transpose();
    }
    const int bodies[4] = {3, 1, 0, 2};
    for (const int width : widths) {
      std::vector<SolverBody> lanes = solver;
      std::vector<Mat3> rotations(4, Mat3::Zero());
      const BodyFields f = bodyFields(lanes, motions, rotations);
      if (width == 4) integrate_w4::prepareRotations(f, bodies, 4);
      else if (width == 2) prepareRotations<Double2>(f, bodies, 4);
      else prepareRotations<double>(f, bodies, 4);
      for (int l = 0; l < 4; ++l)
        ASSERT_TRUE(sameBits(rotations[l], reference_R[l]) &&
                    sameBits(lanes[l].inv_inertia, reference_world[l]))
            << "width " << width << ", body " << l << ", case " << n;
    }
  }
}

// The pose part of finishBody (finishPoses) against its Eigen code, at each width: displacements
// that round to ties, to zero from below (nearbyint keeps the sign), and a carry beyond the
// world range, where the position is left off the grid.
TEST(IntegrateKernel, StepEndPosesGiveTheEigenBitsAtEachWidth) {
  std::mt19937_64 rng(63);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> widths = {1, 2};
  if (cpuHasAvx2()) widths.push_back(4);
  const double ulp = 1.0 / kPositionGrid;
  for (int n = 0; n < 5000; ++n) {
    std::vector<SolverBody> solver(4);
    std::vector<BodyMotion> motions(4);
    for (int l = 0; l < 4; ++l) {
      SolverBody& s = solver[l];
      BodyMotion& m = motions[l];
      m.x = snapPosition(Vec3(100.0 * u(rng), 100.0 * u(rng), 100.0 * u(rng)));
      m.x_carry = 0.5 * ulp * Vec3(u(rng), u(rng), u(rng));
      m.q = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
      s.dp = 0.01 * Vec3(u(rng), u(rng), u(rng));
      s.dq = Quat(1.0 + 0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng)).normalized();
      switch ((n + l) % 6) {
        case 1: s.dp = Vec3(2.5, -3.5, 0.5) * ulp, m.x_carry.setZero(); break;  // ties
        case 2:  // -0.3 ulp snaps to -0, and -0 + -0 keeps the sign
          s.dp = Vec3(-0.3 * ulp, 0.0, 0.0), m.x_carry.setZero(), m.x.x() = -0.0;
          break;
        case 3: m.x_carry.x() = 1e300; break;  // beyond the range: left as is
        case 4: s.dq = Quat(0.0, 0.0, 0.0, 0.0); break;     // the unnormalisable branch
        default: break;
      }
    }
    std::vector<BodyMotion> reference = motions;
    for (int l = 0; l < 4; ++l) {
      BodyMotion& m = reference[l];
      const Vec3 d = solver[l].dp + m.x_carry, on_grid = snapPosition(d);
      m.x_carry = d - on_grid;
      m.x += on_grid;
      m.q = (solver[l].dq * m.q).normalized();
    }
    const int bodies[4] = {1, 3, 2, 0};
    for (const int width : widths) {
      std::vector<BodyMotion> lanes = motions;
      std::vector<Mat3> rotations(4);
      const BodyFields f = bodyFields(solver, lanes, rotations);
      if (width == 4) integrate_w4::finishPoses(f, bodies, 4, kPositionGrid, kWorldRange);
      else if (width == 2) finishPoses<Double2>(f, bodies, 4, kPositionGrid, kWorldRange);
      else finishPoses<double>(f, bodies, 4, kPositionGrid, kWorldRange);
      for (int l = 0; l < 4; ++l)
        ASSERT_TRUE(sameBits(lanes[l].x, reference[l].x) &&
                    sameBits(lanes[l].x_carry, reference[l].x_carry) &&
                    sameBits(lanes[l].q.coeffs(), reference[l].q.coeffs()))
            << "width " << width << ", body " << l << ", case " << n;
    }
  }
}

}  // namespace
}  // namespace ragdoll_sim
