// contact_separations_kernel.hpp against updateSeparations (contact_solver.cpp): each lane's
// double separations must have its bits at two lanes (SSE2) and four (AVX, where the CPU has
// AVX2), and the float lanes those bits rounded; padding lanes and the points past a lane's
// count keep what the block held.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "body.hpp"
#include "contact_separations.hpp"
#include "contact_solver.hpp"
#include "lane_width.hpp"

namespace ragdoll_sim {
namespace {

bool sameBits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }
bool sameBits(float x, float y) { return std::memcmp(&x, &y, sizeof x) == 0; }

TEST(ContactSeparations, TwoAndFourLanesGiveTheScalarBits) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  std::vector<int> widths = {2};
  if (cpuHasAvx2()) widths.push_back(4);
  constexpr int kBodies = 12;
  constexpr float kUntouched = 12345.0f;
  for (int n = 0; n < 3000; ++n) {
    std::vector<SolverBody> bodies(kBodies);
    for (int b = 0; b < kBodies; ++b) {
      SolverBody& s = bodies[b];
      s.dp = 0.05 * vec();
      s.dq = Quat(1.0 + 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)).normalized();
      if (b == 0) {  // a static body: identity, no displacement, signed zeros
        s.dp = Vec3(0.0, -0.0, 0.0);
        s.dq = Quat::Identity();
      }
    }
    // Lanes used from the front, the rest padding (at least one used).
    const int used = 1 + n % kRowBlock;
    std::vector<ContactConstraint> cs(used);
    ContactSeparationBlock geometry{};
    ContactBlock block{};
    for (int p = 0; p < kBlockPoints; ++p)
      for (int l = 0; l < kRowBlock; ++l) block.point[p].separation[l] = kUntouched;
    for (int l = 0; l < used; ++l) {
      ContactConstraint& cc = cs[l];
      cc.a = (n + l) % kBodies;
      cc.b = (n + 3 * l + 1) % kBodies;
      cc.normal = vec().normalized();
      cc.count = 1 + (n + l) % kBlockPoints;
      block.points = std::max(block.points, int32_t(cc.count));
      geometry.body_a[l] = cc.a;
      geometry.body_b[l] = cc.b;
      geometry.count[l] = cc.count;
      for (int k = 0; k < 3; ++k) geometry.n[k][l] = cc.normal[k];
      for (int p = 0; p < cc.count; ++p) {
        ContactConstraintPoint& pt = cc.points[p];
        pt.rA = 0.3 * vec();
        pt.rB = 0.3 * vec();
        pt.base_separation = 0.01 * u(rng);
        for (int k = 0; k < 3; ++k) {
          geometry.r_a[p][k][l] = pt.rA[k];
          geometry.r_b[p][k][l] = pt.rB[k];
        }
        geometry.base[p][l] = pt.base_separation;
      }
      // what a lane's points past its count hold: another lane's, last step's
      for (int p = cc.count; p < kBlockPoints; ++p) geometry.base[p][l] = u(rng);
    }
    std::vector<ContactConstraint> reference = cs;
    for (ContactConstraint& cc : reference) updateSeparations(bodies[cc.a], bodies[cc.b], cc);
    for (const int width : widths) {
      ContactSeparationBlock g = geometry;
      ContactBlock b = block;
      const LaneBodies view = laneBodies(bodies.data());
      if (width == 4) contact_separations_w4::update(&g, &b, 1, view);
      else contact_separations_w2::update(&g, &b, 1, view);
      for (int l = 0; l < kRowBlock; ++l) {
        const int count = l < used ? cs[l].count : 0;
        for (int p = 0; p < kBlockPoints; ++p) {
          const std::string where = "width " + std::to_string(width) + ", lane " +
                                    std::to_string(l) + ", point " + std::to_string(p) +
                                    ", case " + std::to_string(n);
          if (p >= count) {
            ASSERT_TRUE(sameBits(b.point[p].separation[l], kUntouched)) << where;
            continue;
          }
          const double s = reference[l].points[p].separation;
          ASSERT_TRUE(sameBits(g.separation[p][l], s)) << where;
          ASSERT_TRUE(sameBits(b.point[p].separation[l], float(s))) << where;
        }
      }
    }
  }
}

}  // namespace
}  // namespace ragdoll_sim
