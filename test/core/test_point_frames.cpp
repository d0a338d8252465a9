// point_frames_kernel.hpp against the parts' own Eigen code: the anchors, their error, a hinge's
// U and C, and the advanced angles with their limit errors must have the bits of
// PointPart::refresh / error, HingeAxisPart::refresh and AngleAxes::advance at two lanes (SSE2)
// and four (AVX, where the CPU has AVX2), whatever the inputs. The anchor error is checked as
// the float lanes take it (the frame keeps no double copy).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "body.hpp"
#include "joint_angle_axes.hpp"
#include "lane_width.hpp"
#include "part_hinge_axis.hpp"
#include "part_point.hpp"
#include "point_frames.hpp"

namespace ragdoll_sim {
namespace {

bool sameBits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }
bool sameBits(float x, float y) { return std::memcmp(&x, &y, sizeof x) == 0; }

// One lane's joint: its parts as the scalar code holds them.
struct LaneJoint {
  int a = 0, b = 0;
  PointPart point;
  bool hinge = false;
  HingeAxisPart axis;
  AngleAxes<kAngleRows> angles;
};

void fill(PointFrameBlock& f, int i, const LaneJoint& j) {
  for (int k = 0; k < 3; ++k) {
    f.r_a0[k][i] = j.point.rA0[k];
    f.r_b0[k][i] = j.point.rB0[k];
    f.center[k][i] = j.point.delta_center[k];
    f.a1[k][i] = j.hinge ? j.axis.a1_0[k] : 0.0;
    f.b2[k][i] = j.hinge ? j.axis.b2_0[k] : 0.0;
    f.c2[k][i] = j.hinge ? j.axis.c2_0[k] : 0.0;
  }
  for (int r = 0; r < kAngleRows; ++r) {
    const bool used = r < j.angles.count;
    for (int k = 0; k < 3; ++k) f.angle_j[r][k][i] = used ? j.angles.rows[r][k] : 0.0;
    f.angles[r][i] = used ? j.angles.angles[r] : 0.0;
    f.lower[r][i] = j.angles.lower[r];
    f.upper[r][i] = j.angles.upper[r];
    f.limited[r][i] = used && j.angles.limits_enabled ? 1.0 : 0.0;
  }
  f.body_a[i] = j.a;
  f.body_b[i] = j.b;
}

// The limit errors point_lanes.cpp puts for row r (putAngleErrors).
float lowerError(const AngleAxes<kAngleRows>& ax, int r) {
  const bool limit = r < ax.count && ax.limits_enabled;
  return float(std::min(limit ? ax.angles[r] - ax.lower[r] : 1.0, kFarOpen));
}
float upperError(const AngleAxes<kAngleRows>& ax, int r) {
  const bool limit = r < ax.count && ax.limits_enabled;
  return float(std::min(limit ? ax.upper[r] - ax.angles[r] : 1.0, kFarOpen));
}

TEST(PointFrames, TwoAndFourLanesGiveThePartsBits) {
  std::mt19937_64 rng(74);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  std::vector<int> widths = {2};
  if (cpuHasAvx2()) widths.push_back(4);
  constexpr int kBodies = 12;
  int advanced = 0;
  for (int n = 0; n < 2000; ++n) {
    const double h = (n % 5 + 1) * 1e-3;
    std::vector<SolverBody> bodies(kBodies);
    for (int b = 0; b < kBodies; ++b) {
      SolverBody& s = bodies[b];
      s.w = 20.0 * vec();
      s.dp = 0.05 * vec();
      s.dq = Quat(1.0 + 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)).normalized();
      if (b == 0) {  // a static body: identity, at rest, signed zeros
        s.w = Vec3(0.0, -0.0, 0.0);
        s.dp.setZero();
        s.dq = Quat::Identity();
      }
    }
    // Lanes used from the front, the rest padding (at least one used).
    const int used = 1 + n % kRowBlock;
    std::vector<LaneJoint> joints(used);
    PointFrameBlock frame{};
    PointRowBlock rows{};
    rows.axis_rows = n % 3 != 0;
    rows.angle_rows = n % 4;
    for (int i = 0; i < kRowBlock; ++i) rows.body_a[i] = rows.body_b[i] = -1;
    for (int i = 0; i < used; ++i) {
      LaneJoint& j = joints[i];
      j.a = (n + i) % kBodies;
      j.b = (n + 3 * i + 1) % kBodies;
      j.point.rA0 = 0.3 * vec();
      j.point.rB0 = 0.3 * vec();
      j.point.delta_center = 0.5 * vec();
      j.hinge = rows.axis_rows && (i + n) % 2 == 0;
      if (j.hinge) {
        j.axis.a1_0 = vec().normalized();
        j.axis.a2_0 = vec().normalized();
        j.axis.b2_0 = anyPerpendicular(j.axis.a2_0);
        j.axis.c2_0 = j.axis.a2_0.cross(j.axis.b2_0);
      }
      AngleAxes<kAngleRows>& ax = j.angles;
      ax.count = (n + i) % 5 == 0 ? 0 : rows.angle_rows;  // 0: near gimbal lock
      ax.limits_enabled = (n + i) % 3 != 0;
      for (int r = 0; r < kAngleRows; ++r) {
        ax.rows[r] = vec();
        ax.angles[r] = u(rng);
        ax.lower[r] = (n + r) % 7 == 0 ? -1e9 : -0.5 + 0.1 * u(rng);  // -1e9: open for good
        ax.upper[r] = 0.5 + 0.1 * u(rng);
      }
      // the block holds the movable bodies; the frames every body
      rows.body_a[i] = j.a == 0 ? -1 : j.a;
      rows.body_b[i] = j.b == 0 ? -1 : j.b;
      if (rows.body_a[i] < 0 && rows.body_b[i] < 0) rows.body_b[i] = j.b = 1;
      fill(frame, i, j);
    }
    for (int i = used; i < kRowBlock; ++i) {  // padding: the first lane's bodies, all zeros
      frame.body_a[i] = joints[0].a;
      frame.body_b[i] = joints[0].b;
    }
    const bool advance = n % 2 == 1;
    // The scalar parts.
    std::vector<LaneJoint> reference = joints;
    for (LaneJoint& j : reference) {
      const SolverBody &A = bodies[j.a], &B = bodies[j.b];
      j.point.refresh(A, B);
      if (j.hinge) j.axis.refresh(A, B);
      if (advance) j.angles.advance(A, B, h);
    }
    for (const int width : widths) {
      PointFrameBlock f = frame;
      PointRowBlock r = rows;
      const LaneBodies view = laneBodies(bodies.data());
      if (width == 4) point_frames_w4::refresh(&f, &r, 1, view, advance, h);
      else point_frames_w2::refresh(&f, &r, 1, view, advance, h);
      for (int i = 0; i < used; ++i) {
        const LaneJoint& j = reference[i];
        const Vec3 C = j.point.error(bodies[j.a], bodies[j.b]);
        const std::string where =
            "width " + std::to_string(width) + ", lane " + std::to_string(i) + ", case " +
            std::to_string(n);
        for (int k = 0; k < 3; ++k) {
          ASSERT_TRUE(sameBits(f.r_a[k][i], j.point.rA[k]) && sameBits(f.r_b[k][i], j.point.rB[k]))
              << where;
          ASSERT_TRUE(sameBits(r.r_a[k][i], float(j.point.rA[k])) &&
                      sameBits(r.r_b[k][i], float(j.point.rB[k])) &&
                      sameBits(r.error[k][i], float(C[k])))
              << where;
        }
        if (j.hinge) {
          for (int k = 0; k < 3; ++k)
            ASSERT_TRUE(sameBits(f.u1[k][i], j.axis.u1[k]) && sameBits(f.u2[k][i], j.axis.u2[k]) &&
                        sameBits(r.axis_u1[k][i], float(j.axis.u1[k])) &&
                        sameBits(r.axis_u2[k][i], float(j.axis.u2[k])))
                << where;
          for (int k = 0; k < 2; ++k)
            ASSERT_TRUE(sameBits(f.axis_c[k][i], j.axis.C[k]) &&
                        sameBits(r.axis_error[k][i], float(j.axis.C[k])))
                << where;
        } else if (rows.axis_rows) {
          for (int k = 0; k < 3; ++k) ASSERT_EQ(r.axis_u1[k][i], 0.0f) << where;
        }
        if (!advance) continue;
        for (int row = 0; row < rows.angle_rows; ++row) {
          if (row < j.angles.count) {
            ASSERT_TRUE(sameBits(f.angles[row][i], j.angles.angles[row])) << where;
            ++advanced;
          }
          ASSERT_TRUE(sameBits(r.limit_c[row][0][i], lowerError(j.angles, row)) &&
                      sameBits(r.limit_c[row][1][i], upperError(j.angles, row)))
              << where << ", row " << row;
        }
      }
      // Padding lanes past the last group of `width` lanes are not written.
      for (int i = (used + width - 1) / width * width; i < kRowBlock; ++i)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(r.r_a[k][i], 0.0f);
    }
  }
  EXPECT_GT(advanced, 1000);
}

}  // namespace
}  // namespace ragdoll_sim
