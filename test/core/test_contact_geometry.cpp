// The double-lane kernels of the wide contact blocks' geometry against the scalar code they
// replace: contact_separations_kernel.hpp against updateSeparations and
// contact_row_lanes_kernel.hpp against contactRow (contact_solver.hpp). At two lanes (SSE2)
// and four (AVX, where the CPU has AVX2) the double results must have the scalar bits and the
// float lanes those bits rounded. A row in double lanes is compared in double too: a row one
// ulp off rounds to the same float almost always, so the floats alone would not see the order
// of a sum. The scalar friction clamp's shortcut (insideCone) must skip only square roots that
// would not clamp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "body.hpp"
#include "contact_row_lanes_kernel.hpp"
#include "contact_geometry.hpp"
#include "contact_solver.hpp"
#include "lane_width.hpp"

namespace ragdoll_sim {
namespace {

bool sameBits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }
bool sameBits(float x, float y) { return std::memcmp(&x, &y, sizeof x) == 0; }

std::vector<int> laneWidths() {
  std::vector<int> widths = {2};
  if (cpuHasAvx2()) widths.push_back(4);
  return widths;
}

// A moved body with inverse mass 1e-2 to 1e2 and a symmetric positive inverse inertia, or a
// static one (identity, no displacement with signed zeros, inverse mass and inertia 0).
SolverBody randomBody(std::mt19937_64& rng, bool is_static) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SolverBody s;
  if (is_static) {
    s.dp = Vec3(0.0, -0.0, 0.0);
    return s;
  }
  s.dp = 0.05 * Vec3(u(rng), u(rng), u(rng));
  s.dq = Quat(1.0 + 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)).normalized();
  s.inv_mass = std::pow(10.0, 2.0 * u(rng));
  Mat3 m;
  for (int i = 0; i < 9; ++i) m.data()[i] = u(rng);
  s.inv_inertia = std::pow(10.0, 2.0 * u(rng)) * (m * m.transpose() + 0.1 * Mat3::Identity());
  return s;
}

// Case n: one block of random manifolds (lanes used from the front, the rest padding) between
// 12 bodies, body 0 static, as prepare leaves it: the constraints and the block's geometry.
// The points past a lane's count and the padding lanes hold another step's values.
struct BlockCase {
  static constexpr int kBodies = 12;
  std::vector<SolverBody> bodies;
  std::vector<ContactConstraint> cs;  // one per used lane
  ContactGeometryBlock geometry{};
  ContactBlock block{};

  BlockCase(int n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const auto vec = [&] { return Vec3(u(rng), u(rng), u(rng)); };
    for (int b = 0; b < kBodies; ++b) bodies.push_back(randomBody(rng, b == 0));
    cs.resize(1 + n % kRowBlock);
    for (int l = 0; l < kRowBlock; ++l) {
      for (int k = 0; k < 3; ++k) geometry.t[0][k][l] = u(rng);
      for (int p = 0; p < kBlockPoints; ++p) {
        for (int k = 0; k < 3; ++k) {
          geometry.r_a[p][k][l] = u(rng);
          geometry.r_b[p][k][l] = u(rng);
        }
        geometry.base[p][l] = u(rng);
      }
    }
    for (int l = 0; l < int(cs.size()); ++l) {
      ContactConstraint& cc = cs[l];
      cc.a = (n + l) % kBodies;
      cc.b = (n + 3 * l + 1) % kBodies;
      cc.normal = vec().normalized();
      cc.tangent[0] = cc.normal.cross(vec()).normalized();
      cc.tangent[1] = cc.normal.cross(cc.tangent[0]);
      cc.count = 1 + (n + 2 * l) % kBlockPoints;
      block.points = std::max(block.points, int32_t(cc.count));
      geometry.body_a[l] = cc.a;
      geometry.body_b[l] = cc.b;
      geometry.count[l] = cc.count;
      for (int k = 0; k < 3; ++k) {
        geometry.n[k][l] = cc.normal[k];
        for (int j = 0; j < 2; ++j) geometry.t[j][k][l] = cc.tangent[j][k];
      }
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
    }
  }
  int count(int lane) const { return lane < int(cs.size()) ? cs[lane].count : 0; }
};

std::string where(int width, int lane, int point, int n) {
  return "width " + std::to_string(width) + ", lane " + std::to_string(lane) + ", point " +
         std::to_string(point) + ", case " + std::to_string(n);
}

// Padding lanes and the points past a lane's count keep what the block held.
TEST(ContactSeparations, TwoAndFourLanesGiveTheScalarBits) {
  std::mt19937_64 rng(77);
  constexpr float kUntouched = 12345.0f;
  for (int n = 0; n < 3000; ++n) {
    BlockCase c(n, rng);
    for (int p = 0; p < kBlockPoints; ++p)
      for (int l = 0; l < kRowBlock; ++l) c.block.point[p].separation[l] = kUntouched;
    std::vector<ContactConstraint> reference = c.cs;
    for (ContactConstraint& cc : reference) updateSeparations(c.bodies[cc.a], c.bodies[cc.b], cc);
    for (const int width : laneWidths()) {
      ContactGeometryBlock g = c.geometry;
      ContactBlock b = c.block;
      const LaneBodies view = laneBodies(c.bodies.data());
      if (width == 4) contact_geometry_w4::updateSeparations(&g, &b, 1, view);
      else contact_geometry_w2::updateSeparations(&g, &b, 1, view);
      for (int l = 0; l < kRowBlock; ++l)
        for (int p = 0; p < kBlockPoints; ++p) {
          if (p >= c.count(l)) {
            ASSERT_TRUE(sameBits(b.point[p].separation[l], kUntouched)) << where(width, l, p, n);
            continue;
          }
          const double s = reference[l].points[p].separation;
          ASSERT_TRUE(sameBits(g.separation[p][l], s)) << where(width, l, p, n);
          ASSERT_TRUE(sameBits(b.point[p].separation[l], float(s))) << where(width, l, p, n);
        }
    }
  }
}

TEST(ContactRowLanes, DoubleLanesGiveTheScalarRowBits) {
  using double_lanes::Double2;
  std::mt19937_64 rng(79);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 100000; ++n) {
    SolverBody bodies[4];
    for (int b = 0; b < 4; ++b) bodies[b] = randomBody(rng, n % 5 == 0 && b % 2 == 0);
    ContactRow expect[2];
    Double2 ra[3], rb[3], d[3], ia[9], ib[9], masses;
    for (int l = 0; l < 2; ++l) {  // lane l: bodies 2 l and 2 l + 1
      const SolverBody &A = bodies[2 * l], &B = bodies[2 * l + 1];
      const Vec3 rA = 0.3 * Vec3(u(rng), u(rng), u(rng)), rB = 0.3 * Vec3(u(rng), u(rng), u(rng));
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      expect[l] = contactRow(A, B, rA, rB, dir);
      for (int k = 0; k < 3; ++k) {
        ra[k][l] = rA[k];
        rb[k][l] = rB[k];
        d[k][l] = dir[k];
      }
      for (int k = 0; k < 9; ++k) {
        ia[k][l] = A.inv_inertia.data()[k];
        ib[k][l] = B.inv_inertia.data()[k];
      }
      masses[l] = A.inv_mass + B.inv_mass;
    }
    Double2 ang_a[3], ang_b[3], iang_a[3], iang_b[3];
    const Double2 mass =
        contact_row_lanes::row(ra, rb, d, ia, ib, masses, ang_a, ang_b, iang_a, iang_b);
    for (int l = 0; l < 2; ++l) {
      const std::string at = "case " + std::to_string(n) + ", lane " + std::to_string(l);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(sameBits(ang_a[k][l], expect[l].angA[k])) << at;
        ASSERT_TRUE(sameBits(ang_b[k][l], expect[l].angB[k])) << at;
        ASSERT_TRUE(sameBits(iang_a[k][l], expect[l].iangA[k])) << at;
        ASSERT_TRUE(sameBits(iang_b[k][l], expect[l].iangB[k])) << at;
      }
      ASSERT_TRUE(sameBits(mass[l], expect[l].mass)) << at;
    }
  }
}

// Every float of row lane l equals what `expect` gives for (field, component); field 4: mass.
template <class F>
void expectRow(const ContactRowLanes& r, int l, F&& expect, const std::string& at) {
  const float(*const fields[4])[kRowBlock] = {r.ang_a, r.ang_b, r.iang_a, r.iang_b};
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(sameBits(fields[f][k][l], expect(f, k))) << at << ", field " << f;
  ASSERT_TRUE(sameBits(r.mass[l], expect(4, 0))) << at << ", mass";
}

// The points past a lane's count and the padding lanes get zero rows and mass; the rest of a
// point (separation, impulses) is left as it was.
TEST(ContactRowLanes, TwoAndFourLanesGiveTheScalarBits) {
  std::mt19937_64 rng(78);
  constexpr float kUntouched = 12345.0f;
  constexpr double kMassUntouched = 54321.0;
  for (int n = 0; n < 3000; ++n) {
    BlockCase c(n, rng);
    for (int p = 0; p < kBlockPoints; ++p)
      for (int l = 0; l < kRowBlock; ++l) {
        c.block.point[p].separation[l] = kUntouched;
        c.geometry.normal_mass[p][l] = kMassUntouched;
      }
    for (const int width : laneWidths()) {
      ContactGeometryBlock g = c.geometry;
      ContactBlock b = c.block;
      const LaneBodies view = laneBodies(c.bodies.data());
      if (width == 4) contact_geometry_w4::prepareRows(&g, &b, 1, view);
      else contact_geometry_w2::prepareRows(&g, &b, 1, view);
      for (int l = 0; l < kRowBlock; ++l)
        for (int p = 0; p < kBlockPoints; ++p) {
          const std::string at = where(width, l, p, n);
          ASSERT_TRUE(sameBits(b.point[p].separation[l], kUntouched)) << at;
          if (p >= b.points) {  // not read by the solver: not written
            ASSERT_TRUE(sameBits(g.normal_mass[p][l], kMassUntouched)) << at;
            continue;
          }
          for (int j = 0; j < 3; ++j) {
            const ContactRowLanes& lanes = b.point[p].row[j];
            if (p >= c.count(l)) {
              expectRow(lanes, l, [](int, int) { return 0.0f; }, at);
              continue;
            }
            const ContactConstraint& cc = c.cs[l];
            const Vec3& d = j == 0 ? cc.normal : cc.tangent[j - 1];
            const ContactRow r =
                contactRow(c.bodies[cc.a], c.bodies[cc.b], cc.points[p].rA, cc.points[p].rB, d);
            const Vec3* v[4] = {&r.angA, &r.angB, &r.iangA, &r.iangB};
            expectRow(lanes, l, [&](int f, int k) { return float(f < 4 ? (*v[f])[k] : r.mass); },
                      at + ", row " + std::to_string(j));
            if (j == 0) {
              ASSERT_TRUE(sameBits(g.normal_mass[p][l], r.mass)) << at;
            }
          }
        }
    }
  }
}

// insideCone says a point is inside the friction cone only where sqrt(mag2) > limit is false,
// for magnitudes within a few ulp of the edge and limits from subnormal to overflowing squares,
// and it says so for points clearly inside (else the shortcut would never be taken).
TEST(FrictionCone, ShortcutSkipsNoClamp) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double offsets[] = {-1e-3, -1e-9, -0x1p-40, -0x1p-44, -0x1p-50, -0x1p-52,
                            0.0,   0x1p-52, 0x1p-50,  1e-9};
  int clear_inside = 0, clear_count = 0;
  for (int i = 0; i < 20000; ++i) {
    const double limit = std::ldexp(1.0 + unit(rng), int(-540.0 + 1080.0 * unit(rng)));
    for (const double rel : offsets) {
      for (int ulps = -3; ulps <= 3; ++ulps) {
        double mag2 = limit * limit * (1.0 + rel);
        for (int k = 0; k < std::abs(ulps); ++k)
          mag2 = std::nextafter(mag2, ulps > 0 ? HUGE_VAL : 0.0);
        if (insideCone(mag2, limit)) {
          ASSERT_FALSE(std::sqrt(mag2) > limit) << "mag2 " << mag2 << " limit " << limit;
        }
        if (rel == -1e-3 && limit * limit >= std::numeric_limits<double>::min() &&
            std::isfinite(limit * limit)) {
          ++clear_count;
          clear_inside += insideCone(mag2, limit);
        }
      }
    }
  }
  EXPECT_GT(clear_count, 1000);
  EXPECT_EQ(clear_inside, clear_count);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(insideCone(0.0, 0.0));  // a speculative point: the cone is a point
  EXPECT_FALSE(insideCone(0.0, 1e-170));  // limit^2 below the normal range
  EXPECT_FALSE(insideCone(nan, 1.0));
  EXPECT_FALSE(insideCone(0.25, nan));
  EXPECT_TRUE(insideCone(1e300, 1e200));  // limit^2 overflows: any finite root is below limit
}

}  // namespace
}  // namespace ragdoll_sim
