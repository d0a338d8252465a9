// integrate_kernel.hpp against the Eigen expressions it replaces: one body (double) and two
// bodies (Double2 lanes) must give the same bits as the Eigen code, whatever the inputs.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "integrate_kernel.hpp"
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

void scalarStep(double h, BodyState& b) {
  advanceRotation(h, 0.5 * h, b.v.data(), b.dp.data(), b.w.data(), b.dq.coeffs().data(),
                  b.R.data(), b.inertia.data(), b.q.coeffs().data());
  finishRotation(b.R.data(), b.inv_inertia.data(), b.w.data());
}

void pairStep(double h, BodyState& a, BodyState& b) {
  Double2 v[3], dp[3], w[3], dq[4], R[9], inertia[9], inv_inertia[9], q[4];
  gather<3>(a.v.data(), b.v.data(), v);
  gather<3>(a.dp.data(), b.dp.data(), dp);
  gather<3>(a.w.data(), b.w.data(), w);
  gather<4>(a.dq.coeffs().data(), b.dq.coeffs().data(), dq);
  gather<9>(a.R.data(), b.R.data(), R);
  gather<9>(a.inertia.data(), b.inertia.data(), inertia);
  gather<9>(a.inv_inertia.data(), b.inv_inertia.data(), inv_inertia);
  gather<4>(a.q.coeffs().data(), b.q.coeffs().data(), q);
  advanceRotation(Double2{h, h}, Double2{0.5 * h, 0.5 * h}, v, dp, w, dq, R, inertia, q);
  finishRotation(R, inv_inertia, w);
  scatter<3>(dp, a.dp.data(), b.dp.data());
  scatter<3>(w, a.w.data(), b.w.data());
  scatter<4>(dq, a.dq.coeffs().data(), b.dq.coeffs().data());
  scatter<9>(R, a.R.data(), b.R.data());
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

TEST(IntegrateKernel, OneAndTwoBodiesGiveTheEigenBits) {
  std::mt19937_64 rng(60);
  for (int n = 0; n < 20000; ++n) {
    const double h = (n % 7 + 1) * 1.0 / 240.0;
    BodyState a = randomBody(rng, n % 5), b = randomBody(rng, (n / 5) % 5);
    BodyState ra = a, rb = b, sa = a;
    referenceStep(h, ra);
    referenceStep(h, rb);
    scalarStep(h, sa);
    pairStep(h, a, b);
    ASSERT_TRUE(sameBits(sa, ra)) << "scalar, case " << n;
    ASSERT_TRUE(sameBits(a, ra)) << "lane 0, case " << n;
    ASSERT_TRUE(sameBits(b, rb)) << "lane 1, case " << n;
  }
}

}  // namespace
}  // namespace ragdoll_sim
